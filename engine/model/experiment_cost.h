// Output-error residuals of one whole experiment as a Ceres cost function.
//
// Parameter blocks (all of size 1): the model parameters in model order, then the initial
// state in state order, then the experiment's input corrections (input_noise.h; a block holds
// c / sigma_c). A parameter block holds theta = value / scale. Residual i, for sample i of
// output c at node k:
//   r_i = w_i (y_c(x_k, u_k, p) - y_i)          (wrapped to (-pi, pi] for angle outputs)
// and, with a per-sample robust loss rho, r~_i = sign(r_i) sqrt(rho(r_i^2)) so that
// 1/2 sum r~^2 = 1/2 sum rho(r^2) (Ceres applies losses per block, not per sample).
//
// Derivatives: the whole experiment is simulated on Jets carrying the derivatives along the
// blocks Ceres asks a Jacobian for (constant blocks cost nothing): once, on the smallest
// compiled Jet size that holds them all, or, beyond kMaxJetSize directions, in as few passes
// as it takes, each seeding an equal share of the directions.
//
// With a cache (ExperimentCostOptions), an evaluation at the values of a recent one is copied
// from it (evaluation_cache.h: residuals alone from either kind, a Jacobian from a Jet one).
#pragma once

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "ceres/ceres.h"
#include "engine/base/check.h"
#include "engine/model/evaluation_cache.h"
#include "engine/model/experiment.h"
#include "engine/model/simulate.h"

namespace vesselid {

// Jet sizes compiled for each model. Even sizes only: a Jet's derivative vector is then whole
// SSE2 packets of two doubles, and an odd width is slower than the next even one (cargo,
// 300 001 samples, residual + Jacobian: 1 direction 75 ms vs 2: 72 ms, 3: 102 vs 4: 95,
// 5: 123 vs 6: 112, 7: 133 vs 8: 121; tests/benchmarks/benchmark_solve_cost). The unused
// directions carry zero derivatives. Every size is a whole simulation compiled per model (the
// 6-DOF family's handle took 397 s of CPU with sizes up to 80); beyond 32 directions a second
// pass costs little more than the wider Jet would, since the derivative arithmetic grows with
// the width either way and only the scalar part is repeated.
using JetSizes = std::integer_sequence<int, 2, 4, 6, 8, 12, 16, 24, 32>;
inline constexpr int kMaxJetSize = 32;
// Experiments with input corrections have a direction per knot (32 for a minute of record
// at the default spacing) besides the parameters and states, so nearly always more than 16:
// two sizes suffice. Each size is a whole simulation compiled per model (8 and 24 took a
// sixth of the 6-DOF handle's compile time and a quarter of a Nomoto handle's).
using CorrectedJetSizes = std::integer_sequence<int, 16, 32>;

// The most directions an experiment without input corrections can ask for: every parameter
// and state of the model. A model whose parameter count has a ceiling states it as
// `static constexpr int kMaxParameters` (ModelAdapter checks it against ModelInfo); the Jet
// sizes above the first one that holds them all are then never compiled for it (a Nomoto
// model needs 6 or 8 directions at most: half the sizes, half its handle's compile time).
template <class Model, class = void>
struct MaxPlainDirections : std::integral_constant<int, kMaxJetSize> {
  static constexpr bool kStated = false;
};
template <class Model>
struct MaxPlainDirections<Model, std::void_t<decltype(Model::kMaxParameters)>>
    : std::integral_constant<int, Model::kMaxParameters + Model::kNumStates> {
  static constexpr bool kStated = true;
};

// The smallest of `Sizes` holding `directions` (the largest if none does).
template <int... Sizes>
constexpr int SmallestJetSizeFor(int directions, std::integer_sequence<int, Sizes...>) {
  int size = 0;
  ((size == 0 && Sizes >= directions ? size = Sizes : 0), ...);
  return size == 0 ? kMaxJetSize : size;
}

struct ExperimentCostOptions {
  // Keeps the recent evaluations (evaluation_cache.h); null: every evaluation simulates. Sized
  // by the caller for the experiment's samples and blocks; must outlive the cost function.
  EvaluationCache* cache = nullptr;
  EvaluationCounts* counts = nullptr;  // counts evaluations (may be null)
};

template <class Model>
class ExperimentCost final : public ceres::CostFunction {
 public:
  // `experiment` and `loss` (may be null) must outlive the cost function.
  ExperimentCost(const Model& model, const Experiment* experiment,
                 std::vector<double> parameter_scales, const ceres::LossFunction* loss,
                 ExperimentCostOptions options = {})
      : model_(model),
        experiment_(experiment),
        scales_(std::move(parameter_scales)),
        wrapped_(experiment->wrapped_outputs),
        loss_(loss),
        counts_(options.counts),
        cache_(options.cache) {
    num_parameters_ = static_cast<int>(scales_.size());
    num_corrections_ = experiment->num_input_corrections();
    for (const InputCorrectionGrid& g : experiment->input_corrections) {
      for (int j = 0; j < g.count; ++j) correction_scales_.push_back(g.sigma);
    }
    for (int i = 0; i < NumBlocks(); ++i) {
      mutable_parameter_block_sizes()->push_back(1);
    }
    set_num_residuals(experiment->num_samples());
    VESSELID_CHECK(cache_ == nullptr || (cache_->num_residuals() == num_residuals() &&
                                         cache_->num_blocks() == NumBlocks()));
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    int directions = 0;
    if (jacobians != nullptr) {
      for (int b = 0; b < NumBlocks(); ++b) directions += jacobians[b] != nullptr;
    }
    if (directions == 0) jacobians = nullptr;
    const long revision = experiment_->weights_revision;
    if (cache_ != nullptr && cache_->Lookup(parameters, revision, residuals, jacobians)) {
      if (counts_ != nullptr) ++counts_->hits;
      return true;
    }
    bool ok = true;
    if (directions == 0) {
      if (counts_ != nullptr) ++counts_->simulations;
      ok = num_corrections_ == 0
               ? EvaluateScalar<double, false>(parameters, residuals, nullptr, 0, 0)
               : EvaluateScalar<double, true>(parameters, residuals, nullptr, 0, 0);
    } else {
      // passes of equal width: 40 directions as 2 x 20 (on Jets of 24), not 32 + 8
      const int passes = (directions + kMaxJetSize - 1) / kMaxJetSize;
      const int width = (directions + passes - 1) / passes;
      for (int first = 0; ok && first < directions; first += width) {
        if (counts_ != nullptr) ++counts_->jet_simulations;
        ok = num_corrections_ == 0
                 ? Dispatch<false>(JetSizes{}, width, first, parameters, residuals, jacobians)
                 : Dispatch<true>(CorrectedJetSizes{}, width, first, parameters, residuals,
                                  jacobians);
      }
    }
    if (ok && cache_ != nullptr) cache_->Store(parameters, revision, residuals, jacobians);
    return ok;
  }

 private:
  int NumBlocks() const { return num_parameters_ + Model::kNumStates + num_corrections_; }

  // Simulates on the smallest Jet of at least `width` directions, seeding the directions
  // first, first + 1, ... of the blocks asked for (in block order).
  template <bool kCorrected, int... Sizes>
  bool Dispatch(std::integer_sequence<int, Sizes...>, int width, int first,
                double const* const* parameters, double* residuals, double** jacobians) const {
    bool ok = false, done = false;
    (EvaluateOnJet<kCorrected, Sizes>(width, first, parameters, residuals, jacobians, &done, &ok),
     ...);
    VESSELID_CHECK(done);  // width <= kMaxJetSize (and the model's ceiling) by construction
    return ok;
  }

  // One size of Dispatch's: evaluates if no smaller size did and this one holds `width`.
  template <bool kCorrected, int kSize>
  void EvaluateOnJet(int width, int first, double const* const* parameters, double* residuals,
                     double** jacobians, bool* done, bool* ok) const {
    constexpr int kLargest = SmallestJetSizeFor(MaxPlainDirections<Model>::value, JetSizes{});
    if constexpr (kCorrected || kSize <= kLargest) {
      if (*done || kSize < width) return;
      *done = true;
      *ok = EvaluateScalar<ceres::Jet<double, kSize>, kCorrected>(parameters, residuals, jacobians,
                                                                  first, width);
    }
  }

  // Seeds block b with derivative `slope` in its direction (if it has one).
  template <class T>
  static void Seed(double value, double slope, int direction, T* out) {
    if constexpr (std::is_same_v<T, double>) {
      *out = value;
    } else {
      *out = T(value);
      if (direction >= 0) out->v[direction] = slope;
    }
  }

  // On Jets: the blocks asked for whose rank among them is in [first_direction,
  // first_direction + width) carry a direction; the others' Jacobians are left to the other
  // passes. kCorrected: the experiment has input corrections (num_corrections_ > 0).
  template <class T, bool kCorrected>
  bool EvaluateScalar(double const* const* parameters, double* residuals, double** jacobians,
                      int first_direction, int width) const {
    constexpr int n = Model::kNumStates;
    std::vector<int> direction(NumBlocks(), -1);
    int count = 0;
    if constexpr (!std::is_same_v<T, double>) {
      int rank = 0;
      for (int b = 0; b < NumBlocks(); ++b) {
        if (jacobians[b] == nullptr) continue;
        if (rank >= first_direction && rank < first_direction + width) direction[b] = count++;
        ++rank;
      }
    }
    std::vector<T> p(num_parameters_);
    for (int i = 0; i < num_parameters_; ++i) {
      Seed(parameters[i][0] * scales_[i], scales_[i], direction[i], &p[i]);
    }
    std::array<T, n> x;
    for (int i = 0; i < n; ++i) {
      Seed(parameters[num_parameters_ + i][0], 1.0, direction[num_parameters_ + i], &x[i]);
    }

    std::vector<T> c(num_corrections_);
    for (int j = 0; j < num_corrections_; ++j) {
      const int b = num_parameters_ + n + j;
      Seed(parameters[b][0] * correction_scales_[j], correction_scales_[j], direction[b], &c[j]);
    }

    const Experiment& e = *experiment_;
    std::array<T, Model::kNumOutputs> y;
    auto visit = [&](int k, const T* state, const auto* u) {
      const int first = e.node_first_sample[k], last = e.node_first_sample[k + 1];
      if (first == last) return;
      model_.Output(state, u, p.data(), y.data());
      for (int i = first; i < last; ++i) {
        const ExperimentSample& s = e.samples[i];
        T r = y[s.output] - s.value;
        if (!wrapped_.empty() && wrapped_[s.output]) {
          r -= 2.0 * M_PI * std::round(ScalarPart(r) / (2.0 * M_PI));
        }
        r *= s.weight;
        StoreResidual(r, i, direction, count, residuals, jacobians);
      }
    };
    bool simulated = false;
    if constexpr (kCorrected) {
      simulated = SimulateCorrected(c.data(), p.data(), x.data(), visit);
    } else {
      simulated = SimulateExperiment(model_, e, p.data(), x.data(), visit);
    }
    if (!simulated) return false;
    for (int i = 0; i < e.num_samples(); ++i) {
      if (!std::isfinite(residuals[i])) return false;
    }
    return true;
  }

  // Kept out of EvaluateScalar so that the plain path keeps its inlining (measured: inlined,
  // the corrected simulation made the compiler outline the Jet arithmetic of the RK4 step).
  template <class T, class Visitor>
  __attribute__((noinline)) bool SimulateCorrected(const T* c, const T* p, T* x,
                                                   Visitor& visit) const {
    return SimulateExperimentCorrected(model_, *experiment_, c, p, x, visit);
  }

  template <class T>
  void StoreResidual(const T& r, int i, const std::vector<int>& direction, int count,
                     double* residuals, double** jacobians) const {
    const double value = ScalarPart(r);
    double slope = 1.0;  // d r~ / d r
    double robust = value;
    if (loss_ != nullptr && value != 0.0) {
      double rho[3];
      loss_->Evaluate(value * value, rho);
      const double root = std::sqrt(rho[0]);
      robust = std::copysign(root, value);
      slope = rho[1] * std::abs(value) / root;
    }
    residuals[i] = robust;
    if constexpr (!std::is_same_v<T, double>) {
      for (int b = 0; b < NumBlocks(); ++b) {
        if (direction[b] >= 0) jacobians[b][i] = slope * r.v[direction[b]];
      }
    }
  }

  const Model model_;
  const Experiment* experiment_;
  std::vector<double> scales_;
  std::vector<bool> wrapped_;  // per output: residual wrapped to (-pi, pi] (empty: none)
  const ceres::LossFunction* loss_;
  int num_parameters_ = 0;
  int num_corrections_ = 0;
  std::vector<double> correction_scales_;  // sigma_c of each correction block
  EvaluationCounts* counts_;
  EvaluationCache* cache_;
};

}  // namespace vesselid

// The filter-error method's cost of one experiment: the negative log-likelihood of the
// Kalman filter's innovations (kalman_filter.h),
//
//   -log L = 1/2 sum_i (nu_i^2 / S_i + log S_i) + const,
//
// as a Ceres least-squares cost with two residuals per sample,
//
//   r_2i = nu_i / sqrt(S_i),      r_2i+1 = sqrt(log S_i + c_j)      (j: the sample's output)
//
// so that 1/2 sum r^2 = -log L + const and the gradient J'r is the likelihood's exactly. The
// offsets c_j (FilterOffsets) keep log S + c_j >= 1 while solving (c_j = 1 - log floor_j);
// re-centred at the optimum to 1 - min log S_j, J'J is the Fisher information (expected
// Hessian: E[nu^2] = S makes the r_2i rows give (dnu)^2/S + (dS)^2/(4 S^2), the r_2i+1 rows
// another (dS)^2/(4 S^2)), from which the intervals come with s^2 = 1.
//
// Parameter blocks (all of size 1): the model parameters (value / scale), the initial state,
// then the noise parameters (DisturbanceLayout order, value / scale). Derivatives: the whole
// filter runs on Jets, one pass on the smallest Jet size holding the directions asked for, or
// equal passes of at most kMaxJetSize.
#pragma once

#include <utility>
#include <vector>

#include "ceres/ceres.h"
#include "engine/base/check.h"
#include "engine/model/experiment_cost.h"
#include "engine/model/kalman_filter.h"

namespace vesselid {

// Jet sizes of the filter (each compiles the filter once per model).
using FilterJetSizes = std::integer_sequence<int, 8, 16, 32>;

// The likelihood residuals' offsets c_j per model output, shared by a problem's costs;
// `revision` changes with them (the costs' cached evaluations are of the old ones).
struct FilterOffsets {
  std::vector<double> c;
  long revision = 0;
};

template <class Model>
class FilterErrorCost final : public ceres::CostFunction {
 public:
  // `experiment`, `layout` and `offsets` must outlive the cost. `p0`: per model state, the
  // initial variance (0 where the initial state is estimated).
  FilterErrorCost(const Model& model, const Experiment* experiment,
                  std::vector<double> parameter_scales, const DisturbanceLayout* layout,
                  std::vector<double> noise_scales, std::vector<double> p0,
                  const FilterOffsets* offsets, ExperimentCostOptions options = {})
      : model_(model),
        experiment_(experiment),
        scales_(std::move(parameter_scales)),
        layout_(layout),
        noise_scales_(std::move(noise_scales)),
        p0_(std::move(p0)),
        offsets_(offsets),
        counts_(options.counts),
        cache_(options.cache) {
    num_parameters_ = static_cast<int>(scales_.size());
    VESSELID_CHECK(static_cast<int>(noise_scales_.size()) == layout_->size());
    VESSELID_CHECK(static_cast<int>(p0_.size()) == Model::kNumStates);
    for (int i = 0; i < NumBlocks(); ++i) mutable_parameter_block_sizes()->push_back(1);
    set_num_residuals(2 * experiment->num_samples());
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
    // Ceres' bounded trust region asks twice at one point (evaluation_cache.h).
    const long revision = offsets_->revision;
    if (cache_ != nullptr && cache_->Lookup(parameters, revision, residuals, jacobians)) {
      if (counts_ != nullptr) ++counts_->hits;
      return true;
    }
    bool ok = true;
    if (directions == 0) {
      if (counts_ != nullptr) ++counts_->simulations;
      ok = Run<double>(parameters, residuals, nullptr, 0, 0);
    } else {
      const int passes = (directions + kMaxJetSize - 1) / kMaxJetSize;
      const int width = (directions + passes - 1) / passes;
      for (int first = 0; ok && first < directions; first += width) {
        if (counts_ != nullptr) ++counts_->jet_simulations;
        ok = Dispatch(FilterJetSizes{}, width, first, parameters, residuals, jacobians);
      }
    }
    if (ok && cache_ != nullptr) cache_->Store(parameters, revision, residuals, jacobians);
    return ok;
  }

 private:
  int NumBlocks() const { return num_parameters_ + Model::kNumStates + layout_->size(); }

  template <int... Sizes>
  bool Dispatch(std::integer_sequence<int, Sizes...>, int width, int first,
                double const* const* parameters, double* residuals, double** jacobians) const {
    bool ok = false, done = false;
    auto one = [&](auto size) {
      constexpr int kSize = decltype(size)::value;
      if (done || kSize < width) return;
      done = true;
      ok = Run<ceres::Jet<double, kSize>>(parameters, residuals, jacobians, first, width);
    };
    (one(std::integral_constant<int, Sizes>{}), ...);
    VESSELID_CHECK(done);
    return ok;
  }

  template <class T>
  static void Seed(double value, double slope, int direction, T* out) {
    if constexpr (std::is_same_v<T, double>) {
      *out = value;
    } else {
      *out = T(value);
      if (direction >= 0) out->v[direction] = slope;
    }
  }

  template <class T>
  bool Run(double const* const* parameters, double* residuals, double** jacobians,
           int first_direction, int width) const {
    using std::log;
    using std::sqrt;
    constexpr int n = Model::kNumStates;
    const int nt = layout_->size();
    std::vector<int> direction(NumBlocks(), -1);
    if constexpr (!std::is_same_v<T, double>) {
      int rank = 0, count = 0;
      for (int b = 0; b < NumBlocks(); ++b) {
        if (jacobians[b] == nullptr) continue;
        if (rank >= first_direction && rank < first_direction + width) direction[b] = count++;
        ++rank;
      }
    }
    std::vector<T> p(num_parameters_), theta(nt);
    std::array<T, n> x0;
    for (int i = 0; i < num_parameters_; ++i) {
      Seed(parameters[i][0] * scales_[i], scales_[i], direction[i], &p[i]);
    }
    for (int i = 0; i < n; ++i) {
      Seed(parameters[num_parameters_ + i][0], 1.0, direction[num_parameters_ + i], &x0[i]);
    }
    for (int i = 0; i < nt; ++i) {
      const int b = num_parameters_ + n + i;
      Seed(parameters[b][0] * noise_scales_[i], noise_scales_[i], direction[b], &theta[i]);
    }
    const std::vector<double>& offset = offsets_->c;
    auto visit = [&](int i, const T& nu, const T& S) {
      const int j = experiment_->samples[i].output;
      const T root = sqrt(S);
      const T r1 = nu / root;
      const T log_term = log(S) + offset[j];
      const T r2 = sqrt(log_term > 0.0 ? log_term : T(0.0));
      residuals[2 * i] = ScalarPart(r1);
      residuals[2 * i + 1] = ScalarPart(r2);
      if constexpr (!std::is_same_v<T, double>) {
        for (int b = 0; b < NumBlocks(); ++b) {
          if (direction[b] < 0) continue;
          jacobians[b][2 * i] = r1.v[direction[b]];
          jacobians[b][2 * i + 1] = ScalarPart(r2) > 0.0 ? r2.v[direction[b]] : 0.0;
        }
      }
    };
    auto node = [](int, const T*, const double*) {};
    if (!RunKalmanFilter(model_, *experiment_, *layout_, p.data(), x0.data(), p0_.data(),
                         theta.data(), visit, node)) {
      return false;
    }
    for (int i = 0; i < 2 * experiment_->num_samples(); ++i) {
      if (!std::isfinite(residuals[i])) return false;
    }
    return true;
  }

  const Model model_;
  const Experiment* experiment_;
  std::vector<double> scales_;
  const DisturbanceLayout* layout_;
  std::vector<double> noise_scales_;
  std::vector<double> p0_;
  const FilterOffsets* offsets_;
  EvaluationCounts* counts_;
  EvaluationCache* cache_;
  int num_parameters_ = 0;
};

}  // namespace vesselid

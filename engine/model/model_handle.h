// A model behind one small interface, so that the engine can hold any model chosen at run
// time. The virtual calls happen once per experiment evaluation, never per integration step:
// ModelAdapter<Model> instantiates the templated simulation for the concrete model.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "ceres/ceres.h"
#include "engine/base/check.h"
#include "engine/model/damping_inertia_form.h"
#include "engine/model/experiment.h"
#include "engine/model/experiment_cost.h"
#include "engine/model/filter_error_cost.h"
#include "engine/model/filter_innovations.h"
#include "engine/model/expression.h"
#include "engine/model/model.h"
#include "engine/model/omitted_terms.h"
#include "engine/model/regression_form.h"

namespace vesselid {

class ModelHandle {
 public:
  virtual ~ModelHandle() = default;
  virtual const ModelInfo& info() const = 0;

  // Output-error cost of one experiment (see experiment_cost.h for the block layout).
  virtual ceres::CostFunction* NewExperimentCost(const Experiment* experiment,
                                                 std::vector<double> parameter_scales,
                                                 const ceres::LossFunction* loss,
                                                 ExperimentCostOptions options = {}) const = 0;

  // The filter-error method's cost of one experiment (filter_error_cost.h for the block
  // layout); `layout` and `offsets` must outlive it.
  virtual ceres::CostFunction* NewFilterErrorCost(const Experiment* experiment,
                                                  std::vector<double> parameter_scales,
                                                  const DisturbanceLayout* layout,
                                                  std::vector<double> noise_scales,
                                                  std::vector<double> p0,
                                                  const FilterOffsets* offsets,
                                                  ExperimentCostOptions options = {}) const = 0;

  // The filter run in double (filter_innovations.h): innovations, their variances and the
  // k-step-ahead predictions. False if the filter diverges.
  virtual bool FilterInnovations(const Experiment& experiment, const double* p, const double* x0,
                                 const double* p0, const DisturbanceLayout& layout,
                                 const double* theta, int prediction_steps,
                                 FilterRun* run) const = 0;

  // The likelihood's score and information for candidate terms the model may lack, at c = 0
  // (omitted_terms.h; `directions` index [p, x0, theta, c]). False if the filter diverges.
  virtual bool ScoreOmittedTerms(const Experiment& experiment, const double* p, const double* x0,
                                 const double* p0, const DisturbanceLayout& layout,
                                 const double* theta, const std::vector<OmittedTerm>& terms,
                                 const std::vector<int>& directions,
                                 OmittedTermScore* score) const = 0;

  // Simulates in double from x0 with parameters p; `outputs` gets every model output at every
  // node (row-major, nodes x outputs). False if the simulation diverges; the nodes it did not
  // reach are then NaN (DivergenceTime, metrics.h). `corrections`: the experiment's input
  // corrections (input_noise.h; null: none added to its latent inputs).
  virtual bool SimulateOutputs(const Experiment& experiment, const double* p, const double* x0,
                               std::vector<double>* outputs,
                               const double* corrections = nullptr) const = 0;

  // The right-hand side and output map in double, for simulators and tools (not the hot path).
  virtual bool Derivative(const double* x, const double* u, const double* p,
                          double* xdot) const = 0;
  virtual void Output(const double* x, const double* u, const double* p, double* y) const = 0;
  // The same recorded on the current expression tape (expression.h), for the C export: the
  // model's own equations, each decision an outcome of the tape's script.
  virtual bool Derivative(const symbolic::Expression* x, const symbolic::Expression* u,
                          const symbolic::Expression* p, symbolic::Expression* xdot) const = 0;
  virtual void Output(const symbolic::Expression* x, const symbolic::Expression* u,
                      const symbolic::Expression* p, symbolic::Expression* y) const = 0;

  // Physical admissibility of parameter values (empty when admissible, or when the model
  // states no conditions). `state_limits` (may be null: unknown): the operating range of the
  // records (operating_range.h: per state the largest |x| they take it to, then per input its
  // smallest and largest value), over which a condition on a function of the state or input
  // (damping that must not feed the motion, a thrust law monotone in its command) is judged;
  // null judges it for every value.
  virtual std::vector<std::string> Admissibility(const double* p,
                                                 const double* state_limits = nullptr) const = 0;

  // Doubts the model family's physics raise about the estimate's structure over the operating
  // range (same layout): a feature the data do not support, e.g. a dead zone whose branch
  // bends the wrong way beyond it. Empty when none or when the model states none.
  virtual std::vector<std::string> StructureDoubts(const double* p,
                                                   const double* operating_range) const = 0;

  // Per state the largest |x| of a simulation in double from x0 over the experiment's nodes,
  // folded into `max_abs` (num_states values, max with what it holds). False if it diverges.
  virtual bool StateLimits(const Experiment& experiment, const double* p, const double* x0,
                           double* max_abs) const = 0;

  // Start values of the states from outputs measured at t0 and their rates (NaN where not
  // measured); x holds the defaults and keeps what the model cannot derive.
  virtual void GuessState(const double* y, const double* ydot, double* x) const = 0;

  // Equation-error form for the least-squares stage (regression_form.h); null when the model
  // has none. The other three members are only called when it has one.
  virtual const RegressionForm* regression_form() const = 0;
  virtual void Regressors(const double* p, RegressionRecord* record,
                          std::vector<Eigen::MatrixXd>* phi) const = 0;
  virtual void Coefficients(const double* p, double* theta) const = 0;
  virtual int Region(const double* u) const = 0;

  // Damping-inertia form for the step-regression stage (damping_inertia_form.h); null when
  // the model has none.
  virtual const DampingInertiaForm* damping_inertia_form() const = 0;
};

// Detects a model's optional
// `std::vector<std::string> Admissibility(const double* p, const double* state_limits) const`.
template <class Model, class = void>
struct HasAdmissibility : std::false_type {};
template <class Model>
struct HasAdmissibility<
    Model, std::void_t<decltype(std::declval<const Model&>().Admissibility(nullptr, nullptr))>>
    : std::true_type {};

// `std::vector<std::string> StructureDoubts(const double* p, const double* range) const`.
template <class Model, class = void>
struct HasStructureDoubts : std::false_type {};
template <class Model>
struct HasStructureDoubts<
    Model, std::void_t<decltype(std::declval<const Model&>().StructureDoubts(nullptr, nullptr))>>
    : std::true_type {};

// Detects a model's optional `void GuessState(const double* y, const double* ydot, double* x)
// const`.
template <class Model, class = void>
struct HasGuessState : std::false_type {};
template <class Model>
struct HasGuessState<Model, std::void_t<decltype(std::declval<const Model&>().GuessState(
                                nullptr, nullptr, nullptr))>> : std::true_type {};

// Detects a model's optional equation-error form (`RegressionForm Regression() const` and the
// members listed in regression_form.h).
template <class Model, class = void>
struct HasRegression : std::false_type {};
template <class Model>
struct HasRegression<Model, std::void_t<decltype(std::declval<const Model&>().Regression())>>
    : std::true_type {};

// Detects a model's optional damping-inertia form (`DampingInertiaForm DampingInertia() const`).
template <class Model, class = void>
struct HasDampingInertia : std::false_type {};
template <class Model>
struct HasDampingInertia<
    Model, std::void_t<decltype(std::declval<const Model&>().DampingInertia())>>
    : std::true_type {};

template <class Model>
class ModelAdapter final : public ModelHandle {
 public:
  explicit ModelAdapter(Model model) : model_(std::move(model)), info_(model_.Info()) {
    // Jets are compiled up to the model's stated ceiling only (experiment_cost.h).
    if constexpr (MaxPlainDirections<Model>::kStated) {
      VESSELID_CHECK(static_cast<int>(info_.parameters.size()) + Model::kNumStates <=
                     MaxPlainDirections<Model>::value);
    }
    if constexpr (HasRegression<Model>::value) {
      form_ = model_.Regression();
      has_form_ = true;
    }
    if constexpr (HasDampingInertia<Model>::value) {
      damping_inertia_ = model_.DampingInertia();
      has_damping_inertia_ = true;
    }
  }

  const ModelInfo& info() const override { return info_; }

  ceres::CostFunction* NewExperimentCost(const Experiment* experiment,
                                         std::vector<double> parameter_scales,
                                         const ceres::LossFunction* loss,
                                         ExperimentCostOptions options = {}) const override {
    return new ExperimentCost<Model>(model_, experiment, std::move(parameter_scales), loss,
                                     options);
  }

  ceres::CostFunction* NewFilterErrorCost(const Experiment* experiment,
                                          std::vector<double> parameter_scales,
                                          const DisturbanceLayout* layout,
                                          std::vector<double> noise_scales, std::vector<double> p0,
                                          const FilterOffsets* offsets,
                                          ExperimentCostOptions options = {}) const override {
    return new FilterErrorCost<Model>(model_, experiment, std::move(parameter_scales), layout,
                                      std::move(noise_scales), std::move(p0), offsets, options);
  }

  bool FilterInnovations(const Experiment& experiment, const double* p, const double* x0,
                         const double* p0, const DisturbanceLayout& layout, const double* theta,
                         int prediction_steps, FilterRun* run) const override {
    return RunFilterInnovations(model_, experiment, p, x0, p0, layout, theta, prediction_steps,
                                run);
  }

  bool ScoreOmittedTerms(const Experiment& experiment, const double* p, const double* x0,
                         const double* p0, const DisturbanceLayout& layout, const double* theta,
                         const std::vector<OmittedTerm>& terms, const std::vector<int>& directions,
                         OmittedTermScore* score) const override {
    return vesselid::ScoreOmittedTerms(model_, experiment, p,
                                       static_cast<int>(info_.parameters.size()), x0, p0, layout,
                                       theta, terms, directions, score);
  }

  bool SimulateOutputs(const Experiment& e, const double* p, const double* x0,
                       std::vector<double>* outputs,
                       const double* corrections = nullptr) const override {
    constexpr int ny = Model::kNumOutputs;
    outputs->assign(static_cast<size_t>(e.num_nodes()) * ny,
                    std::numeric_limits<double>::quiet_NaN());
    std::array<double, Model::kNumStates> x;
    std::copy(x0, x0 + Model::kNumStates, x.begin());
    double* out = outputs->data();
    auto visit = [&](int k, const double* state, const double* u) {
      model_.Output(state, u, p, out + static_cast<size_t>(k) * ny);
    };
    if (corrections != nullptr && !e.input_corrections.empty()) {
      return SimulateExperimentCorrected(model_, e, corrections, p, x.data(), visit);
    }
    return SimulateExperiment(model_, e, p, x.data(), visit);
  }

  bool Derivative(const double* x, const double* u, const double* p, double* xdot) const override {
    return model_(x, u, p, xdot);
  }
  void Output(const double* x, const double* u, const double* p, double* y) const override {
    model_.Output(x, u, p, y);
  }
  bool Derivative(const symbolic::Expression* x, const symbolic::Expression* u,
                  const symbolic::Expression* p, symbolic::Expression* xdot) const override {
    return model_(x, u, p, xdot);
  }
  void Output(const symbolic::Expression* x, const symbolic::Expression* u,
              const symbolic::Expression* p, symbolic::Expression* y) const override {
    model_.Output(x, u, p, y);
  }

  std::vector<std::string> Admissibility(const double* p,
                                         const double* state_limits = nullptr) const override {
    if constexpr (HasAdmissibility<Model>::value) {
      return model_.Admissibility(p, state_limits);
    } else {
      return {};
    }
  }

  std::vector<std::string> StructureDoubts(const double* p,
                                           const double* operating_range) const override {
    if constexpr (HasStructureDoubts<Model>::value) {
      return model_.StructureDoubts(p, operating_range);
    } else {
      return {};
    }
  }

  bool StateLimits(const Experiment& e, const double* p, const double* x0,
                   double* max_abs) const override {
    std::array<double, Model::kNumStates> x;
    std::copy(x0, x0 + Model::kNumStates, x.begin());
    auto visit = [&](int, const double* state, const double*) {
      for (int i = 0; i < Model::kNumStates; ++i) {
        max_abs[i] = std::max(max_abs[i], std::abs(state[i]));
      }
    };
    return SimulateExperiment(model_, e, p, x.data(), visit);
  }

  void GuessState(const double* y, const double* ydot, double* x) const override {
    if constexpr (HasGuessState<Model>::value) model_.GuessState(y, ydot, x);
  }

  const RegressionForm* regression_form() const override {
    return has_form_ ? &form_ : nullptr;
  }
  void Regressors(const double* p, RegressionRecord* record,
                  std::vector<Eigen::MatrixXd>* phi) const override {
    if constexpr (HasRegression<Model>::value) model_.Regressors(p, record, phi);
  }
  void Coefficients(const double* p, double* theta) const override {
    if constexpr (HasRegression<Model>::value) model_.Coefficients(p, theta);
  }
  int Region(const double* u) const override {
    if constexpr (HasRegression<Model>::value) {
      return model_.Region(u);
    } else {
      return -1;
    }
  }

  const DampingInertiaForm* damping_inertia_form() const override {
    return has_damping_inertia_ ? &damping_inertia_ : nullptr;
  }

  const Model& model() const { return model_; }

 private:
  const Model model_;
  const ModelInfo info_;
  RegressionForm form_;
  bool has_form_ = false;
  DampingInertiaForm damping_inertia_;
  bool has_damping_inertia_ = false;
};

template <class Model>
std::unique_ptr<ModelHandle> MakeModelHandle(Model model) {
  return std::make_unique<ModelAdapter<Model>>(std::move(model));
}

}  // namespace vesselid

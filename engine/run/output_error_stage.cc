#include "engine/run/output_error_stage.h"

#include <chrono>
#include <cstdio>
#include <limits>
#include <memory>

#include "engine/run/continuation.h"
#include "engine/run/records.h"
#include "engine/solve/step_stability.h"

namespace vesselid {
namespace {

constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

// The stage's result from its solved problem; `starts` are the reported start values.
StageResult Collect(const OutputErrorProblem& problem, const std::vector<double>& starts,
                    StageSummary summary) {
  StageResult result;
  result.name = summary.name;
  result.model = problem.model().info().name;
  const std::vector<Variable>& variables = problem.variables();
  const Uncertainty& u = summary.uncertainty;
  for (size_t i = 0; i < variables.size(); ++i) {
    const Variable& v = variables[i];
    Estimate e;
    e.name = v.name;
    e.kind = v.kind == Variable::Kind::kParameter ? EstimateKind::kParameter
                                                  : EstimateKind::kInitialState;
    e.role = v.role;
    e.experiment = v.experiment >= 0 ? problem.experiments()[v.experiment].name : "";
    e.value = v.value();
    e.start = starts[i];
    e.std_error = v.free ? u.StdError(static_cast<int>(i)) : kUnknown;
    e.lower = v.lower;
    e.upper = v.upper;
    for (int index : u.undetermined_variables) e.undetermined |= index == static_cast<int>(i);
    result.estimates.push_back(e);
  }
  if (u.available) {
    for (int index : u.variables) result.correlation_names.push_back(variables[index].name);
    result.correlation = u.correlation;
  }
  result.summary = std::move(summary);
  return result;
}

constexpr int kMaxStepReductions = 3;

// While the estimate's dynamics are faster than the integration step can follow
// (step_stability.h), prepares the experiments with a step that can and refines again from
// the estimate; the step used goes to result->integration_step (0: the configured one).
bool FollowTheDynamics(const RunConfig& config, const StageConfig& stage,
                       const ModelHandle& model, StageOptions options, TrajectoryCache* cache,
                       std::unique_ptr<OutputErrorProblem>* problem, StageSummary* summary,
                       StageResult* result, std::string* error) {
  options.use_global_start = false;
  ExperimentOptions finer = stage.experiment;
  for (int reduction = 0;; ++reduction) {
    const StepStability stability = CheckStepStability(**problem);
    if (stability.worst <= kStepStabilityLimit) return true;
    if (reduction == kMaxStepReductions) {
      summary->notes.push_back("integration step too long for the estimate's dynamics after " +
                               std::to_string(kMaxStepReductions) + " reductions: " +
                               stability.Describe() +
                               "; the estimate may fit the integrator, not the vessel");
      return true;
    }
    finer.max_step = stability.SafeStep();
    char text[128];
    std::snprintf(text, sizeof(text), "integration step reduced to %.3g s and the stage refined "
                  "again: ", finer.max_step);
    summary->notes.push_back(text + stability.Describe());
    std::vector<Experiment> experiments;
    if (!PrepareExperiments(config, stage.experiments, model, finer, cache, &experiments,
                            error)) {
      return false;
    }
    std::vector<ParameterSpec> specs;
    const std::vector<double> values = (*problem)->ParametersOf(0);
    for (size_t i = 0; i < values.size(); ++i) {
      const Variable* shared = nullptr;
      for (const Variable& v : (*problem)->variables()) {
        if (v.kind == Variable::Kind::kParameter && v.index == static_cast<int>(i)) shared = &v;
      }
      ParameterSpec spec;
      spec.name = model.info().parameters[i];
      spec.start = values[i];
      spec.role = shared != nullptr ? shared->role : ParameterRole::kFixed;
      if (shared != nullptr) {
        spec.lower = shared->lower;
        spec.upper = shared->upper;
        spec.scale = shared->scale;
      }
      specs.push_back(spec);
    }
    std::unique_ptr<OutputErrorProblem> refined =
        OutputErrorProblem::Create(&model, std::move(experiments), specs, stage.problem, error);
    if (refined == nullptr) return false;
    refined->SetValues((*problem)->Values());  // per-experiment values and states too
    StageSummary again;
    if (!RunStage(options, refined.get(), &again)) {
      *error = "refinement with the integration step reduced to " + std::to_string(finer.max_step) +
               " s: " + again.message;
      return false;
    }
    again.notes.insert(again.notes.begin(), summary->notes.begin(), summary->notes.end());
    again.name = summary->name;
    *summary = std::move(again);
    *problem = std::move(refined);
    result->integration_step = finer.max_step;
  }
}

}  // namespace

bool RunOutputErrorStage(const RunConfig& config, const StageConfig& stage,
                         const ModelHandle& model, std::vector<ParameterSpec>* resolved,
                         TrajectoryCache* cache, const ProgressCallback& progress,
                         StageResult* result, std::string* error) {
  std::vector<ParameterSpec>& specs = *resolved;
  const std::vector<ParameterSpec> configured = specs;
  std::vector<StateAt> states;
  std::vector<std::string> continuation_notes;
  const auto stage_start = std::chrono::steady_clock::now();
  if (!RunContinuation(config, stage, model, cache, progress, &specs, &states, &continuation_notes,
                       error)) {
    return false;
  }
  std::vector<Experiment> experiments;
  if (!PrepareExperiments(config, stage.experiments, model, stage.experiment, cache, &experiments,
                          error)) {
    return false;
  }
  std::unique_ptr<OutputErrorProblem> problem =
      OutputErrorProblem::Create(&model, std::move(experiments), specs, stage.problem, error);
  if (problem == nullptr) return false;
  // After continuation the stage is refined twice: from the initial states the short
  // segments estimated, and from the data's guess (the latter sometimes finds the lower
  // of two nearby minima; both cost one refinement).
  std::vector<std::vector<double>> extra_starts;
  if (!states.empty()) {
    extra_starts.push_back(problem->Values());
    SetCarriedStates(states, problem.get());
  }
  // Reported starts are the configured ones, not those continuation handed on.
  std::vector<double> starts = problem->Values();
  for (size_t i = 0; i < starts.size(); ++i) {
    const Variable& v = problem->variables()[i];
    if (v.kind == Variable::Kind::kParameter && v.experiment < 0) {
      starts[i] = configured[v.index].start;
    }
  }
  StageOptions options = stage.options;
  options.use_global_start = options.use_global_start && stage.continuation.empty();
  options.local.progress = progress;
  options.global.progress = progress;
  StageSummary summary;
  if (!RunStage(options, problem.get(), &summary, extra_starts)) {
    *error = summary.message;
    return false;
  }
  if (!FollowTheDynamics(config, stage, model, options, cache, &problem, &summary, result, error)) {
    return false;
  }
  summary.notes.insert(summary.notes.begin(), continuation_notes.begin(), continuation_notes.end());
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start).count();
  const double integration_step = result->integration_step;
  *result = Collect(*problem, starts, std::move(summary));
  result->integration_step = integration_step;
  return true;
}

}  // namespace vesselid

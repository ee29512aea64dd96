#include "engine/run/output_error_stage.h"

#include <chrono>
#include <limits>
#include <memory>

#include "engine/run/continuation.h"
#include "engine/run/records.h"

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
  summary.notes.insert(summary.notes.begin(), continuation_notes.begin(), continuation_notes.end());
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start).count();
  *result = Collect(*problem, starts, std::move(summary));
  return true;
}

}  // namespace vesselid

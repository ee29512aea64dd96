#include "engine/pipeline.h"

#include <chrono>
#include <cmath>
#include <limits>

namespace vesselid {

bool PrepareStageExperiments(const RunConfig& config, const StageConfig& stage,
                             TrajectoryCache* cache, std::vector<Experiment>* experiments,
                             std::string* error) {
  experiments->clear();
  const ModelInfo& info = config.model->info();
  for (const std::string& name : stage.experiments) {
    const ExperimentSpec* spec = config.FindExperiment(name);
    // Cached per experiment: degree conversion depends on the experiment's own spec.
    const std::string key = spec->name + "\n" + spec->file;
    auto cached = cache->find(key);
    if (cached == cache->end()) {
      Trajectory trajectory;
      if (!LoadExperimentData(*spec, &trajectory, error)) return false;
      cached = cache->emplace(key, std::move(trajectory)).first;
    }
    const Trajectory& trajectory = cached->second;
    Experiment experiment;
    if (!BuildExperiment(*spec, trajectory, info, stage.experiment, &experiment, error))
      return false;
    experiments->push_back(std::move(experiment));
  }
  return true;
}

namespace {

StageResult Collect(const OutputErrorProblem& problem, const std::vector<double>& starts,
                    StageSummary summary) {
  StageResult result;
  result.name = summary.name;
  const std::vector<Variable>& variables = problem.variables();
  const double kUnknown = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = 0; i < variables.size(); ++i) {
    const Variable& v = variables[i];
    Estimate e;
    e.name = v.name;
    e.kind = v.kind == Variable::Kind::kParameter ? "parameter" : "initial_state";
    e.role = ParameterRoleToString(v.role);
    e.experiment = v.experiment >= 0 ? problem.experiments()[v.experiment].name : "";
    e.value = v.value();
    e.start = starts[i];
    e.std_error = v.free ? summary.uncertainty.StdError(static_cast<int>(i)) : kUnknown;
    e.lower = v.lower;
    e.upper = v.upper;
    result.estimates.push_back(e);
  }
  if (summary.uncertainty.available) {
    for (int index : summary.uncertainty.variables)
      result.correlation_names.push_back(variables[index].name);
    result.correlation = summary.uncertainty.correlation;
  }
  result.summary = std::move(summary);
  return result;
}

}  // namespace

bool RunIdentification(const RunConfig& config, RunResult* result, std::string* error,
                       const StageObserver& observer) {
  const auto start_time = std::chrono::steady_clock::now();
  RunResult run;
  TrajectoryCache cache;
  for (const StageConfig& stage : config.stages) {
    const std::string where = "stage '" + stage.options.name + "': ";
    if (observer) observer(nullptr, stage.options.name);
    std::vector<Experiment> experiments;
    if (!PrepareStageExperiments(config, stage, &cache, &experiments, error)) {
      *error = where + *error;
      return false;
    }
    std::unique_ptr<OutputErrorProblem> problem = OutputErrorProblem::Create(
        config.model.get(), std::move(experiments), stage.parameters, stage.problem, error);
    if (problem == nullptr) {
      *error = where + *error;
      return false;
    }
    const std::vector<double> starts = problem->Values();
    StageSummary summary;
    if (!RunStage(stage.options, problem.get(), &summary)) {
      *error = where + summary.message;
      return false;
    }
    run.stages.push_back(Collect(*problem, starts, std::move(summary)));
    if (observer) observer(&run.stages.back(), "");
  }
  run.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  *result = std::move(run);
  return true;
}

}  // namespace vesselid

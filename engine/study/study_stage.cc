#include "engine/study/study_stage.h"

#include <cmath>
#include <limits>

#include "engine/run/pipeline.h"
#include "engine/run/records.h"
#include "engine/run/stage_weights.h"

namespace vesselid {

std::vector<double> StudyStage::FreeStarts() const {
  std::vector<double> starts;
  for (int index : free) starts.push_back(specs[index].start);
  return starts;
}

bool PrepareStudyStage(const RunConfig& config, const std::string& name, StudyStage* stage,
                       std::string* error, bool solve) {
  int index = -1;
  for (size_t i = 0; i < config.stages.size(); ++i) {
    const StageConfig& s = config.stages[i];
    if (name.empty() ? s.kind == StageConfig::Kind::kOutputError : s.options.name == name) {
      index = static_cast<int>(i);
    }
  }
  if (index < 0) {
    *error = name.empty() ? "the run has no output-error stage to study"
                          : "no stage named '" + name + "'";
    return false;
  }
  const StageConfig& s = config.stages[index];
  if (s.kind != StageConfig::Kind::kOutputError) {
    *error = "stage '" + s.options.name + "' is not an output-error stage";
    return false;
  }
  *stage = StudyStage();
  stage->config = &config;
  stage->stage = &s;
  stage->model = s.model ? s.model.get() : config.model.get();
  StageResult solved;
  if (!ResolveStage(config, index, &stage->specs, nullptr, error, solve ? &solved : nullptr)) {
    return false;
  }
  for (const Estimate& e : solved.estimates) {
    stage->run_optimum[e.name] = e.value;
    stage->run_std_errors[e.name] = e.std_error;
  }
  stage->noise_weights = UsesNoiseWeights(config, s);
  if (!PrepareExperiments(config, s.experiments, *stage->model, StageExperimentOptions(config, s),
                          &stage->records, &stage->experiments, error)) {
    *error = "stage '" + s.options.name + "': " + *error;
    return false;
  }
  stage->options = s.options;
  stage->options.local.num_threads = 1;
  stage->options.global.threads = 1;  // the study's cases already fill the cores
  for (size_t i = 0; i < stage->specs.size(); ++i) {
    if (IsEstimatedOnce(stage->specs[i].role)) {
      stage->free.push_back(static_cast<int>(i));
      stage->free_names.push_back(stage->specs[i].name);
    }
  }
  if (stage->free.empty()) {
    *error = "stage '" + s.options.name + "' estimates no shared parameter";
    return false;
  }
  return true;
}

namespace {

// Variable index of each free shared parameter, in StudyStage::free order.
std::vector<int> FreeVariables(const StudyStage& stage, const OutputErrorProblem& problem) {
  std::vector<int> variables(stage.free.size(), -1);
  for (size_t i = 0; i < problem.variables().size(); ++i) {
    const Variable& v = problem.variables()[i];
    if (v.kind != Variable::Kind::kParameter || v.experiment >= 0) continue;
    for (size_t k = 0; k < stage.free.size(); ++k) {
      if (v.index == stage.free[k]) variables[k] = static_cast<int>(i);
    }
  }
  return variables;
}

}  // namespace

std::vector<double> StudySolve::Values(const StudyStage& stage) const {
  std::vector<double> values;
  for (int v : FreeVariables(stage, *problem)) values.push_back(problem->variables()[v].value());
  return values;
}

std::vector<double> StudySolve::StdErrors(const StudyStage& stage) const {
  std::vector<double> errors;
  for (int v : FreeVariables(stage, *problem)) {
    errors.push_back(problem->variables()[v].free ? summary.uncertainty.StdError(v)
                                                  : std::numeric_limits<double>::quiet_NaN());
  }
  return errors;
}

StudySolve SolveStudyStage(const StudyStage& stage, std::vector<Experiment> experiments,
                           const std::vector<ParameterSpec>& specs, const StageOptions& options,
                           const std::map<std::string, double>* start) {
  StudySolve solve;
  solve.problem = OutputErrorProblem::Create(stage.model, std::move(experiments), specs,
                                             stage.stage->problem, &solve.message);
  if (solve.problem == nullptr) return solve;
  if (start != nullptr) {
    for (const Variable& v : solve.problem->variables()) {
      const auto value = start->find(v.name);
      if (value == start->end() || (v.kind == Variable::Kind::kParameter && !v.free)) continue;
      v.set_value(value->second);
    }
  }
  if (!RunStage(options, solve.problem.get(), &solve.summary) ||
      (stage.noise_weights &&
       !IterateNoiseWeights(options, solve.problem.get(), &solve.summary, &solve.noise))) {
    solve.message = solve.summary.message;
    return solve;
  }
  solve.usable = true;
  return solve;
}

std::map<std::string, double> ValuesByName(const OutputErrorProblem& problem) {
  std::map<std::string, double> values;
  for (const Variable& v : problem.variables()) values[v.name] = v.value();
  return values;
}

bool SimulateSamples(const StudyStage& stage, const std::vector<double>& parameters,
                     std::vector<std::vector<double>>* clean, std::string* error,
                     const std::map<std::string, double>* values) {
  // Every parameter at its value; with `values` the roles stay, so that per-experiment values
  // exist as variables to take theirs.
  std::vector<ParameterSpec> fixed = stage.specs;
  for (size_t i = 0; i < fixed.size(); ++i) {
    fixed[i].start = parameters[i];
    if (values == nullptr) fixed[i].role = ParameterRole::kFixed;
    fixed[i].lower = -std::numeric_limits<double>::infinity();
    fixed[i].upper = std::numeric_limits<double>::infinity();
  }
  auto problem = OutputErrorProblem::Create(stage.model, stage.experiments, fixed,
                                            stage.stage->problem, error);
  if (problem == nullptr) return false;
  if (values != nullptr) {
    for (const Variable& v : problem->variables()) {
      const auto value = values->find(v.name);
      const bool shared = v.kind == Variable::Kind::kParameter && v.experiment < 0;
      if (value != values->end() && !shared) v.set_value(value->second);
    }
  }
  const int ny = static_cast<int>(stage.model->info().outputs.size());
  clean->assign(stage.experiments.size(), {});
  for (size_t e = 0; e < stage.experiments.size(); ++e) {
    const Experiment& experiment = stage.experiments[e];
    const std::vector<double> p = problem->ParametersOf(static_cast<int>(e));
    const std::vector<double> x0 = problem->InitialStateOf(static_cast<int>(e));
    std::vector<double> outputs;
    if (!stage.model->SimulateOutputs(experiment, p.data(), x0.data(), &outputs)) {
      *error = "simulation of experiment '" + experiment.name + "' diverges";
      return false;
    }
    std::vector<double>& values = (*clean)[e];
    values.resize(experiment.samples.size());
    for (int k = 0; k < experiment.num_nodes(); ++k) {
      for (int i = experiment.node_first_sample[k]; i < experiment.node_first_sample[k + 1]; ++i) {
        values[i] = outputs[static_cast<size_t>(k) * ny + experiment.samples[i].output];
      }
    }
  }
  return true;
}

}  // namespace vesselid

#include "engine/run/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <tuple>

#include "engine/run/continuation.h"
#include "engine/model/input_range.h"
#include "engine/run/least_squares_stage.h"
#include "engine/run/step_regression_stage.h"
#include "engine/run/velocity_validation.h"

namespace vesselid {
namespace {

constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

// What the run knows of each parameter so far.
struct Ledger {
  struct Entry {
    std::string stage;
    double value;
    double std_error;
    ParameterRole role;
  };
  std::map<std::string, double> latest;
  std::map<std::string, std::vector<Entry>> estimates;
};

// Full parameter list of a stage: starts resolved from the ledger, unlisted ones fixed there.
bool ResolveParameters(const StageConfig& stage, const ModelInfo& info, const Ledger& ledger,
                       std::vector<ParameterSpec>* specs, std::string* error) {
  specs->clear();
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    const std::string& name = info.parameters[i];
    auto latest = ledger.latest.find(name);
    const double carried = latest != ledger.latest.end() ? latest->second : info.parameter_defaults[i];
    ParameterSpec spec;
    bool listed = false;
    for (const ParameterSpec& s : stage.parameters) {
      if (s.name == name) {
        spec = s;
        listed = true;
      }
    }
    if (!listed) {
      spec.name = name;
      spec.role = ParameterRole::kFixed;
      spec.start = carried;
    } else if (spec.start_from_previous) {
      spec.start = carried;
      spec.start_from_previous = false;
      if (spec.role != ParameterRole::kFixed && (carried < spec.lower || carried > spec.upper)) {
        *error = "parameter '" + name + "': carried start " + std::to_string(carried) +
                 " is outside the stage's bounds [" + std::to_string(spec.lower) + ", " +
                 std::to_string(spec.upper) + "]";
        return false;
      }
    }
    specs->push_back(spec);
  }
  return true;
}

// Simulates `names` with every parameter fixed at `values` (HeldOutProblem).
bool SimulateHeldOut(const RunConfig& config, const ModelHandle& model,
                     const std::vector<std::string>& names, const ExperimentOptions& options,
                     const std::vector<std::string>& free_states, const LocalSolveOptions& local,
                     const std::vector<double>& values, TrajectoryCache* cache,
                     std::vector<ExperimentFit>* fits, std::string* error) {
  std::vector<Experiment> experiments;
  if (!PrepareExperiments(config, names, model, options, cache, &experiments, error)) {
    return false;
  }
  const std::unique_ptr<OutputErrorProblem> problem =
      HeldOutProblem(model, std::move(experiments), free_states, local, values, error);
  return problem != nullptr && EvaluateFit(*problem, fits, error);
}

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
    e.kind = v.kind == Variable::Kind::kParameter ? "parameter" : "initial_state";
    e.role = ParameterRoleToString(v.role);
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

void Record(const StageResult& stage, Ledger* ledger) {
  for (const Estimate& e : stage.estimates) {
    if (e.kind != "parameter" || !e.experiment.empty()) continue;
    ParameterRole role;
    StringToParameterRole(e.role, &role);
    if (!IsEstimatedOnce(role)) continue;
    ledger->latest[e.name] = e.value;
    ledger->estimates[e.name].push_back(
        {stage.name, e.value, e.undetermined ? kUnknown : e.std_error, role});
  }
}

// Information fusion of every parameter that is shared in its last estimating stage and
// determined by at least one stage, with each stage's covariance block of the shared
// parameters it determined. False if a stage has no covariance or the fusion is singular.
bool FuseSharedJointly(const Ledger& ledger, const std::vector<StageResult>& stages,
                       std::map<std::string, std::pair<double, double>>* fused) {
  std::vector<std::string> names;
  for (const auto& [name, entries] : ledger.estimates) {
    bool determined = false;
    for (const Ledger::Entry& e : entries) determined |= std::isfinite(e.std_error);
    if (entries.back().role == ParameterRole::kShared && determined) names.push_back(name);
  }
  if (names.empty()) return true;
  auto position = [&](const std::string& name) {
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  std::vector<SharedEstimate> estimates;
  for (const StageResult& stage : stages) {
    std::vector<const Estimate*> shared;
    for (const Estimate& e : stage.estimates) {
      if (e.kind == "parameter" && e.role == "shared" && e.experiment.empty() &&
          position(e.name) < static_cast<int>(names.size()) && !e.undetermined &&
          std::isfinite(e.std_error)) {
        shared.push_back(&e);
      }
    }
    if (shared.empty()) continue;
    std::vector<int> row;  // each estimate's row in the stage's correlation matrix
    for (const Estimate* e : shared) {
      const auto& c = stage.correlation_names;
      const auto found = std::find(c.begin(), c.end(), e->name);
      if (found == c.end()) return false;
      row.push_back(static_cast<int>(found - c.begin()));
    }
    SharedEstimate estimate;
    const int m = static_cast<int>(shared.size());
    estimate.value.resize(m);
    estimate.covariance.resize(m, m);
    for (int i = 0; i < m; ++i) {
      estimate.parameters.push_back(position(shared[i]->name));
      estimate.value[i] = shared[i]->value;
      for (int j = 0; j < m; ++j) {
        estimate.covariance(i, j) =
            stage.correlation(row[i], row[j]) * shared[i]->std_error * shared[j]->std_error;
      }
    }
    estimates.push_back(std::move(estimate));
  }
  Eigen::VectorXd value;
  Eigen::MatrixXd covariance;
  if (!FuseJointly(static_cast<int>(names.size()), estimates, &value, &covariance)) return false;
  for (size_t i = 0; i < names.size(); ++i) {
    (*fused)[names[i]] = {value[i], std::sqrt(covariance(i, i))};
  }
  return true;
}

std::vector<FinalParameter> Finalise(const ModelInfo& info, const Ledger& ledger,
                                     const std::vector<StageResult>& stages, FusionRule rule) {
  std::map<std::string, std::pair<double, double>> joint;
  const bool joint_ok =
      rule == FusionRule::kInformation && FuseSharedJointly(ledger, stages, &joint);
  std::vector<FinalParameter> parameters;
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    FinalParameter f;
    f.name = info.parameters[i];
    auto found = ledger.estimates.find(f.name);
    if (found == ledger.estimates.end()) {
      auto latest = ledger.latest.find(f.name);
      f.value = latest != ledger.latest.end() ? latest->second : info.parameter_defaults[i];
      // The value a fixed parameter was held at in the last stage.
      for (const StageResult& s : stages) {
        for (const Estimate& e : s.estimates) {
          if (e.name == f.name) f.value = e.value;
        }
      }
      f.std_error = kUnknown;
      f.role = "fixed";
      f.rule = "fixed";
      parameters.push_back(f);
      continue;
    }
    const std::vector<Ledger::Entry>& entries = found->second;
    const Ledger::Entry& last = entries.back();
    f.role = ParameterRoleToString(last.role);
    if (last.role == ParameterRole::kShared) {
      std::vector<double> values, errors;
      for (const Ledger::Entry& e : entries) {
        if (e.role != ParameterRole::kShared) continue;
        values.push_back(e.value);
        errors.push_back(e.std_error);
        f.stages.push_back(e.stage);
      }
      if (joint_ok && joint.count(f.name) > 0) {
        std::tie(f.value, f.std_error) = joint.at(f.name);
        f.rule = "information";
      } else {
        FuseEstimates(values, errors, rule, &f.value, &f.std_error, &f.rule);
        if (rule == FusionRule::kInformation && !joint_ok) f.rule += " (information singular)";
      }
    } else {
      f.value = last.value;
      f.std_error = last.std_error;
      f.stages = {last.stage};
      f.rule = "stage";
    }
    f.undetermined = std::isnan(f.std_error);
    parameters.push_back(f);
  }
  return parameters;
}


// An output-error stage: continuation phases, the problem, RunStage, the result.
bool RunOutputErrorStage(const RunConfig& config, const StageConfig& stage,
                         const ModelHandle& model, std::vector<ParameterSpec>* resolved,
                         TrajectoryCache* cache, const ProgressCallback& progress,
                         StageResult* result, std::string* error) {
  std::vector<ParameterSpec>& specs = *resolved;
  const std::vector<ParameterSpec> configured = specs;
  std::vector<StateAt> states;
  std::vector<std::string> continuation_notes;
  const auto stage_start = std::chrono::steady_clock::now();
  if (!RunContinuation(config, stage, model, cache, progress, &specs, &states,
                       &continuation_notes, error)) {
    return false;
  }
  std::vector<Experiment> experiments;
  if (!PrepareExperiments(config, stage.experiments, model, stage.experiment, cache,
                          &experiments, error)) {
    return false;
  }
  std::unique_ptr<OutputErrorProblem> problem = OutputErrorProblem::Create(
      &model, std::move(experiments), specs, stage.problem, error);
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
  summary.notes.insert(summary.notes.begin(), continuation_notes.begin(),
                       continuation_notes.end());
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start).count();
  *result = Collect(*problem, starts, std::move(summary));
  return true;
}

}  // namespace

std::unique_ptr<OutputErrorProblem> HeldOutProblem(const ModelHandle& model,
                                                   std::vector<Experiment> experiments,
                                                   const std::vector<std::string>& free_states,
                                                   const LocalSolveOptions& local,
                                                   const std::vector<double>& values,
                                                   std::string* error) {
  std::vector<ParameterSpec> fixed;
  for (size_t i = 0; i < values.size(); ++i) {
    ParameterSpec spec;
    spec.name = model.info().parameters[i];
    spec.start = values[i];
    spec.role = ParameterRole::kFixed;
    fixed.push_back(spec);
  }
  OutputErrorOptions problem_options;
  problem_options.free_initial_states = free_states;
  auto problem =
      OutputErrorProblem::Create(&model, std::move(experiments), fixed, problem_options, error);
  if (problem == nullptr) return nullptr;
  if (problem->num_free() > 0) {
    LocalSolveSummary summary;
    if (!RunLocalSolve(local, problem.get(), &summary)) {
      *error = "initial-state estimate: " + summary.message;
      return nullptr;
    }
  }
  return problem;
}

namespace {

bool WholeRecordSpecs(const ExperimentSpec& spec, const Trajectory& data, double segment_length,
                 std::vector<ExperimentSpec>* specs, std::string* error) {
  specs->clear();
  if (!spec.segments.column.empty()) {
    std::vector<SegmentRange> ranges;
    if (!SelectSegments(data, spec.segments, &ranges, error)) {
      *error = "experiment '" + spec.name + "': " + *error;
      return false;
    }
    for (const SegmentRange& range : ranges) {
      ExperimentSpec segment = spec;
      segment.name = spec.name + "@" + std::to_string(range.id);
      segment.t_begin = std::max(spec.t_begin, range.t_begin);
      segment.t_end = std::min(spec.t_end, range.t_end);
      if (segment.t_end > segment.t_begin) specs->push_back(segment);
    }
    return true;
  }
  double length = spec.segment_length;
  if (segment_length > 0.0) length = length > 0.0 ? std::min(length, segment_length) : segment_length;
  if (length <= 0.0) {
    specs->push_back(spec);
    return true;
  }
  const double begin = std::max(spec.t_begin, data.t.front());
  const double end = std::min(spec.t_end, data.t.back());
  int k = 1;
  for (double t0 = begin; t0 + 0.5 * length < end; t0 += length) {
    ExperimentSpec segment = spec;
    segment.name = spec.name + "@" + std::to_string(k++);
    segment.t_begin = t0;
    segment.t_end = std::min(end, t0 + length);
    specs->push_back(segment);
  }
  return true;
}

}  // namespace

std::vector<double> StageParameterValues(const ModelInfo& info, const StageResult& stage) {
  std::vector<double> values;
  for (const std::string& name : info.parameters) {
    for (const Estimate& e : stage.estimates) {
      if (e.kind == "parameter" && e.name == name) {
        values.push_back(e.value);
        break;
      }
    }
  }
  return values;
}

Estimate ParameterEstimate(const ParameterSpec& spec, double value, double std_error) {
  Estimate e;
  e.name = spec.name;
  e.kind = "parameter";
  e.role = ParameterRoleToString(spec.role);
  e.value = value;
  e.start = spec.start;
  e.std_error = std_error;
  e.lower = spec.lower;
  e.upper = spec.upper;
  return e;
}

bool RecordSpecs(const ExperimentSpec& spec, const Trajectory& data, double segment_length,
                 std::vector<ExperimentSpec>* specs, std::string* error) {
  std::vector<ExperimentSpec> whole;
  if (!WholeRecordSpecs(spec, data, segment_length, &whole, error)) return false;
  specs->clear();
  for (const ExperimentSpec& s : whole) {
    if (!SplitByInputRange(s, data, specs, error)) return false;
  }
  return true;
}

namespace {

const Trajectory* LoadCached(const ExperimentSpec& spec, TrajectoryCache* cache,
                             std::string* error) {
  auto cached = cache->find(spec.name);
  if (cached == cache->end()) {
    Trajectory trajectory;
    if (!LoadExperimentData(spec, &trajectory, error)) return nullptr;
    cached = cache->emplace(spec.name, std::move(trajectory)).first;
  }
  return &cached->second;
}

}  // namespace

bool PrepareExperiments(const RunConfig& config, const std::vector<std::string>& names,
                        const ModelHandle& model, const ExperimentOptions& stage_options,
                        TrajectoryCache* cache, std::vector<Experiment>* experiments,
                        std::string* error, double segment_length) {
  const ModelInfo& info = model.info();
  ExperimentOptions options = stage_options;
  options.state_guess = [&model](const double* y, const double* ydot, double* x) {
    model.GuessState(y, ydot, x);
  };
  experiments->clear();
  for (const std::string& name : names) {
    const ExperimentSpec* spec = config.FindExperiment(name);
    const Trajectory* data = LoadCached(*spec, cache, error);
    std::vector<ExperimentSpec> specs;
    if (data == nullptr || !RecordSpecs(*spec, *data, segment_length, &specs, error)) return false;
    for (const ExperimentSpec& s : specs) {
      Experiment experiment;
      if (!BuildExperiment(s, *data, info, options, &experiment, error)) return false;
      experiment.record = name;
      experiments->push_back(std::move(experiment));
    }
  }
  return true;
}

bool PrepareRegressionRecords(const RunConfig& config, const std::vector<std::string>& names,
                              const ModelHandle& model, const RegressionDataOptions& options,
                              TrajectoryCache* cache, std::vector<RegressionRecord>* records,
                              std::string* error) {
  records->clear();
  for (const std::string& name : names) {
    const ExperimentSpec* spec = config.FindExperiment(name);
    const Trajectory* data = LoadCached(*spec, cache, error);
    std::vector<ExperimentSpec> specs;
    if (data == nullptr || !RecordSpecs(*spec, *data, 0.0, &specs, error)) return false;
    for (const ExperimentSpec& s : specs) {
      RegressionRecord record;
      if (!BuildRegressionRecord(s, *data, model, options, &record, error)) return false;
      record.record = name;
      records->push_back(std::move(record));
    }
  }
  return true;
}

namespace {

// Velocity metrics compare with the data as the latest least-squares stage among the first
// `count` prepared it, so that every stage is measured against the same reconstruction.
RegressionDataOptions VelocityData(const RunConfig& config, size_t count) {
  RegressionDataOptions options;
  for (size_t i = 0; i < count; ++i) {
    if (config.stages[i].kind == StageConfig::Kind::kLeastSquares) {
      options = config.stages[i].regression_data;
    }
  }
  return options;
}

// Runs stages [first, count) into `run`, recording every estimate in `ledger`.
bool RunStages(const RunConfig& config, size_t first, size_t count, TrajectoryCache* cache_ptr,
               Ledger* ledger_ptr, RunResult* run_ptr, std::string* error,
               const RunObserver& observer) {
  TrajectoryCache& cache = *cache_ptr;
  Ledger& ledger = *ledger_ptr;
  RunResult& run = *run_ptr;
  for (size_t index = first; index < count; ++index) {
    const StageConfig& stage = config.stages[index];
    const RegressionDataOptions velocity_data = VelocityData(config, index + 1);
    const std::string where = "stage '" + stage.options.name + "': ";
    auto fail = [&](const std::string& what) {
      *error = where + what;
      return false;
    };
    if (observer.stage_started) observer.stage_started(index, stage.options.name);
    const ModelHandle& model = stage.model ? *stage.model : *config.model;
    std::vector<ParameterSpec> specs;
    if (!ResolveParameters(stage, model.info(), ledger, &specs, error)) return fail(*error);
    StageResult stage_result;
    if (stage.kind == StageConfig::Kind::kLeastSquares) {
      if (!RunLeastSquaresStage(config, stage, model, specs, &cache, &stage_result, error)) {
        return fail(*error);
      }
    } else if (stage.kind == StageConfig::Kind::kStepRegression) {
      if (!RunStepRegressionStage(config, stage, model, specs, &cache, &stage_result, error)) {
        return fail(*error);
      }
    } else if (!RunOutputErrorStage(config, stage, model, &specs, &cache, observer.progress,
                                    &stage_result, error)) {
      return fail(*error);
    }
    const std::vector<double> values = StageParameterValues(model.info(), stage_result);
    stage_result.admissibility = model.Admissibility(values.data());
    if (!stage.validation.empty()) {
      if (!SimulateHeldOut(config, model, stage.validation, stage.experiment,
                           stage.problem.free_initial_states, stage.options.local, values,
                           &cache, &stage_result.validation, error)) {
        return fail("validation: " + *error);
      }
      if (model.regression_form() != nullptr &&
          !ValidateVelocities(config, model, stage.validation, velocity_data, values, &cache,
                              &stage_result.velocity_validation, error)) {
        return fail("velocity validation: " + *error);
      }
    }
    Record(stage_result, &ledger);
    run.stages.push_back(std::move(stage_result));
    if (observer.stage_finished && !observer.stage_finished(index, run.stages.back(), error)) {
      return false;
    }
  }
  return true;
}

}  // namespace

namespace {

// Stages [0, result) are all stage `index` needs run before it: the last one estimating a
// parameter that `index` carries (unlisted, or listed without a start).
size_t StagesNeededBefore(const RunConfig& config, size_t index) {
  const StageConfig& stage = config.stages[index];
  const ModelHandle& model = stage.model ? *stage.model : *config.model;
  auto carried = [&](const std::string& name) {
    for (const ParameterSpec& spec : stage.parameters) {
      if (spec.name == name) return spec.start_from_previous;
    }
    return true;
  };
  for (size_t k = index; k-- > 0;) {
    for (const ParameterSpec& spec : config.stages[k].parameters) {
      if (spec.role != ParameterRole::kFixed && model.info().ParameterIndex(spec.name) >= 0 &&
          carried(spec.name)) {
        return k + 1;
      }
    }
  }
  return 0;
}

}  // namespace

bool ResolveStage(const RunConfig& config, size_t index, std::vector<ParameterSpec>* specs,
                  std::vector<StageResult>* before, std::string* error, StageResult* solved) {
  TrajectoryCache cache;
  Ledger ledger;
  RunResult run;
  const size_t needed = StagesNeededBefore(config, index);
  if (!RunStages(config, 0, needed, &cache, &ledger, &run, error, {})) return false;
  const StageConfig& stage = config.stages[index];
  const ModelHandle& model = stage.model ? *stage.model : *config.model;
  if (!ResolveParameters(stage, model.info(), ledger, specs, error)) {
    *error = "stage '" + stage.options.name + "': " + *error;
    return false;
  }
  if (before != nullptr) *before = run.stages;
  if (solved != nullptr) {
    if (!RunStages(config, index, index + 1, &cache, &ledger, &run, error, {})) return false;
    *solved = run.stages.back();
  }
  return true;
}

bool RunIdentification(const RunConfig& config, RunResult* result, std::string* error,
                       const RunObserver& observer, std::vector<StageResult> finished) {
  const auto start_time = std::chrono::steady_clock::now();
  RunResult run;
  TrajectoryCache cache;
  Ledger ledger;
  if (finished.size() > config.stages.size()) {
    *error = "the resumed run has more stages than the config";
    return false;
  }
  for (size_t i = 0; i < finished.size(); ++i) {
    if (finished[i].name != config.stages[i].options.name) {
      *error = "resumed stage " + std::to_string(i + 1) + " is '" + finished[i].name +
               "', the config's is '" + config.stages[i].options.name + "'";
      return false;
    }
    Record(finished[i], &ledger);
    run.stages.push_back(std::move(finished[i]));
  }
  if (!RunStages(config, run.stages.size(), config.stages.size(), &cache, &ledger, &run, error,
                 observer)) {
    return false;
  }
  const RegressionDataOptions velocity_data = VelocityData(config, config.stages.size());
  const ModelInfo& info = config.model->info();
  run.parameters = Finalise(info, ledger, run.stages, config.fusion);
  std::vector<double> final_values;
  for (const FinalParameter& f : run.parameters) final_values.push_back(f.value);
  run.admissibility = config.model->Admissibility(final_values.data());
  if (config.has_final_validation) {
    const FinalValidationConfig& v = config.final_validation;
    const ModelHandle& model = v.model ? *v.model : *config.model;
    if (!SimulateHeldOut(config, model, v.experiments, v.experiment, v.free_initial_states, {},
                         final_values, &cache, &run.final_validation, error)) {
      *error = "final validation: " + *error;
      return false;
    }
    if (model.regression_form() != nullptr) {
      if (!ValidateVelocities(config, model, v.experiments, velocity_data, final_values,
                              &cache,
                              &run.final_velocity_validation, error)) {
        *error = "final velocity validation: " + *error;
        return false;
      }
    }
  }
  run.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  *result = std::move(run);
  return true;
}

}  // namespace vesselid

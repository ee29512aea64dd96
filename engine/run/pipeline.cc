#include "engine/run/pipeline.h"

#include <chrono>

#include "engine/base/memory_budget.h"
#include "engine/model/operating_range.h"
#include "engine/run/display_units.h"
#include "engine/run/held_out.h"
#include "engine/run/held_out_memo.h"
#include "engine/run/integration_step.h"
#include "engine/run/least_squares_stage.h"
#include "engine/run/manoeuvre_runs.h"
#include "engine/run/output_error_stage.h"
#include "engine/run/parameter_ledger.h"
#include "engine/run/prediction_band.h"
#include "engine/run/record_notes.h"
#include "engine/run/records.h"
#include "engine/run/step_regression_stage.h"
#include "engine/run/filter_prediction.h"
#include "engine/run/velocity_validation.h"
#include "engine/run/work_size.h"

namespace vesselid {
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

// The finding of a velocity validation that could not be made, naming the key that drops it.
Finding SkippedVelocityCheck(const std::string& why, const std::string& key) {
  return MakeFinding(FindingKind::kCheckSkipped,
                     "velocity validation skipped: " + why + " (" + key +
                         ": false leaves it out)");
}

// The stage's held-out fits at its estimate and at its start (HeldOutCheck); a stage worse
// than its start is set aside under final: best_validation.
bool ValidateStage(const RunConfig& config, const StageConfig& stage, const ModelHandle& model,
                   const RegressionDataOptions& velocity_data,
                   const std::vector<double>& start_values,
                   const std::vector<double>& previous_values, const std::vector<double>& values,
                   TrajectoryCache* cache, HeldOutMemo* memo, StageResult* result,
                   std::string* error) {
  ExperimentOptions options = stage.experiment;
  options.max_step =
      IntegrationStep(StepUse::kStageValidation, stage.experiment.max_step, {result});
  // The stage and its start are validated alike: held-out runs estimate their own
  // per-experiment parameters in both (or hold them in both).
  HeldOutRequest request;
  request.model = &model;
  request.names = stage.validation;
  request.options = options;
  request.free_states = stage.problem.free_initial_states;
  request.local = stage.options.local;
  request.per_run = PerRunFromStage(*result, model.info(), stage.validation_per_experiment);
  request.start = stage.held_out;
  // At the start the fits alone; at the estimate with the per-experiment estimates and the
  // residual analyses, which the stage reports.
  HeldOutRequest at_estimate = request;
  at_estimate.values = values;
  at_estimate.parameters = at_estimate.residuals = true;
  request.values = start_values;
  std::vector<HeldOutRequest> requests = {at_estimate, request};
  // The previous stages' values where they differ from the start (a parameter restarted from
  // the config): the guard holds the stage against the better of the two.
  const bool previous = previous_values != start_values;
  if (previous) {
    requests.push_back(request);
    requests.back().values = previous_values;
  }
  std::vector<HeldOutAnswer> answers;
  if (!memo->Fit(config, requests, cache, &answers, error)) {
    *error = "validation: " + *error;
    return false;
  }
  result->validation = std::move(answers[0].fits);
  result->held_out_parameters = std::move(answers[0].parameters);
  result->validation_residuals = std::move(answers[0].residuals);
  const std::vector<ExperimentFit>& at_start = answers[1].fits;
  result->held_out = CompareHeldOut(at_start, result->validation);
  if (previous && PredictsBetter(answers[2].fits, at_start)) {
    result->held_out = CompareHeldOut(answers[2].fits, result->validation);
    result->held_out.baseline = "previous";
  }
  if (result->held_out.worse && config.final_choice == FinalChoice::kBestValidation) {
    const bool from_previous = result->held_out.baseline == "previous";
    result->rejected = "worse on held-out data than " + result->held_out.BaselineText() + " (" +
                       DescribeHeldOut(result->held_out, OutputUnits(config),
                                       stage.validation.front()) +
                       "): its estimates are set aside and later stages and the final values "
                       "take " +
                       (from_previous ? "the previous stages' values" : "its start values") +
                       " (final: last would keep them)";
  }
  if (stage.velocity_validation && model.regression_form() != nullptr) {
    std::vector<std::string> diverged;
    std::string why;
    if (!ValidateVelocities(config, model, stage.validation, velocity_data, values, cache,
                            VelocitySteps{stage.experiment.max_step, {result}},
                            &result->velocity_validation, &diverged, &why,
                            stage.options.local.num_threads, &result->held_out_parameters)) {
      // An optional check: the run goes on without it.
      result->velocity_validation.clear();
      diverged.clear();
      result->summary.findings.push_back(SkippedVelocityCheck(why, "stages[].velocity_validation"));
    }
    for (const std::string& d : diverged) {
      result->summary.findings.push_back(
          MakeFinding(FindingKind::kHeldOutDiverged, "velocity validation: " + d));
    }
  }
  PredictHeldOutThroughFilter(config, stage, model, values, cache, result);
  return true;
}

// Runs stages [first, count) into `run`, recording every estimate in `ledger`.
bool RunStages(const RunConfig& config, size_t first, size_t count, TrajectoryCache* cache_ptr,
               HeldOutMemo* memo, ParameterLedger* ledger_ptr, RunResult* run_ptr,
               std::string* error, const RunObserver& observer) {
  TrajectoryCache& cache = *cache_ptr;
  ParameterLedger& ledger = *ledger_ptr;
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
    const ModelHandle& model = config.StageModel(stage);
    std::vector<ParameterSpec> specs;
    if (!ResolveParameters(stage, model.info(), ledger, &specs, error)) return fail(*error);
    std::vector<double> start_values, previous_values;
    for (const ParameterSpec& spec : specs) {
      start_values.push_back(spec.start);
      const auto latest = ledger.latest.find(spec.name);
      previous_values.push_back(latest != ledger.latest.end() ? latest->second : spec.start);
    }
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
    const double* range =
        stage_result.state_limits.empty() ? nullptr : stage_result.state_limits.data();
    stage_result.admissibility = model.Admissibility(values.data(), range);
    stage_result.structure_doubts = model.StructureDoubts(values.data(), range);
    if (!stage.validation.empty() &&
        !ValidateStage(config, stage, model, velocity_data, start_values, previous_values,
                       values, &cache, memo, &stage_result, error)) {
      return fail(*error);
    }
    RecordStageOrItsBaseline(stage_result, &ledger);
    run.stages.push_back(std::move(stage_result));
    if (observer.stage_finished && !observer.stage_finished(index, run.stages.back(), error)) {
      return false;
    }
  }
  return true;
}

// Stages [0, result) are all stage `index` needs run before it: the last one estimating a
// parameter that `index` carries (unlisted, or listed without a start).
size_t StagesNeededBefore(const RunConfig& config, size_t index) {
  const StageConfig& stage = config.stages[index];
  const ModelHandle& model = config.StageModel(stage);
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
  HeldOutMemo memo;
  ParameterLedger ledger;
  RunResult run;
  const size_t needed = StagesNeededBefore(config, index);
  if (!RunStages(config, 0, needed, &cache, &memo, &ledger, &run, error, {})) return false;
  const StageConfig& stage = config.stages[index];
  const ModelHandle& model = config.StageModel(stage);
  if (!ResolveParameters(stage, model.info(), ledger, specs, error)) {
    *error = "stage '" + stage.options.name + "': " + *error;
    return false;
  }
  if (before != nullptr) *before = run.stages;
  if (solved != nullptr) {
    if (!RunStages(config, index, index + 1, &cache, &memo, &ledger, &run, error, {})) {
      return false;
    }
    *solved = run.stages.back();
  }
  return true;
}

bool RunIdentification(const RunConfig& config, RunResult* result, std::string* error,
                       const RunObserver& observer, std::vector<StageResult> finished,
                       TrajectoryCache* records) {
  const auto start_time = std::chrono::steady_clock::now();
  const ScopedMemoryBudget budget(config.limits.memory_bytes);
  RunResult run;
  TrajectoryCache own_cache;
  TrajectoryCache& cache = records != nullptr ? *records : own_cache;
  ParameterLedger ledger;
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
    RecordStageOrItsBaseline(finished[i], &ledger);
    run.stages.push_back(std::move(finished[i]));
  }
  if (!CheckWorkSize(config, &cache, error)) return false;
  std::string stop;
  HeldOutMemo memo;  // the held-out passes of the stages run here (resumed ones aside)
  if (!RunStages(config, run.stages.size(), config.stages.size(), &cache, &memo, &ledger, &run,
                 &stop, observer)) {
    *error = stop;
    if (run.stages.empty()) return false;
    // The finished stages are a result: reported with where and why the run stopped.
    run.stopped_stage = run.stages.size() < config.stages.size()
                            ? config.stages[run.stages.size()].options.name
                            : run.stages.back().name;
    run.stop_message = stop;
  }
  std::vector<StageResult> accepted;
  for (const StageResult& s : run.stages) {
    if (s.rejected.empty()) accepted.push_back(s);
  }
  const ModelInfo& info = config.model->info();
  run.parameters = FinalParameters(info, ledger, accepted, config.fusion);
  std::vector<double> final_values;
  for (const FinalParameter& f : run.parameters) final_values.push_back(f.value);
  // Judged over the operating range any accepted stage of the run's model reached.
  const int nx = static_cast<int>(info.states.size());
  std::vector<double> limits;
  for (const StageResult& s : accepted) {
    if (s.state_limits.size() != static_cast<size_t>(nx) + 2 * info.inputs.size()) continue;
    if (limits.empty()) limits = EmptyOperatingRange(nx, static_cast<int>(info.inputs.size()));
    MergeOperatingRange(s.state_limits, nx, &limits);
  }
  run.admissibility =
      config.model->Admissibility(final_values.data(), limits.empty() ? nullptr : limits.data());
  run.structure_doubts = config.model->StructureDoubts(final_values.data(),
                                                       limits.empty() ? nullptr : limits.data());
  if (config.has_final_validation && run.stopped_stage.empty()) {
    const FinalValidationConfig& v = config.final_validation;
    const ModelHandle& model = v.model ? *v.model : *config.model;
    std::vector<const StageResult*> accepted_stages;
    for (const StageResult& s : accepted) accepted_stages.push_back(&s);
    ExperimentOptions options = v.experiment;
    options.max_step =
        IntegrationStep(StepUse::kFinalValidation, v.experiment.max_step, accepted_stages);
    // Per-experiment parameters come from the last accepted stage that estimated them.
    HeldOutPerRun per_run;
    for (const StageResult& s : accepted) {
      HeldOutPerRun own = PerRunFromStage(s, model.info(), v.per_experiment);
      if (!own.parameters.empty()) per_run = std::move(own);
    }
    HeldOutRequest request;
    request.model = &model;
    request.names = v.experiments;
    request.options = options;
    request.free_states = v.free_initial_states;
    request.per_run = per_run;
    request.start = v.held_out;
    request.values = final_values;
    request.parameters = request.residuals = true;
    std::vector<HeldOutRequest> requests{request};
    if (!v.reference.values.empty()) {  // the reference model, flown alike
      HeldOutRequest reference = request;
      reference.values = v.reference.values;
      reference.parameters = reference.residuals = false;
      requests.push_back(std::move(reference));
    }
    std::vector<HeldOutAnswer> answers;
    if (!memo.Fit(config, requests, &cache, &answers, error)) {
      *error = "final validation: " + *error;
      return false;
    }
    run.final_validation = std::move(answers[0].fits);
    run.final_held_out_parameters = std::move(answers[0].parameters);
    run.final_validation_residuals = std::move(answers[0].residuals);
    if (answers.size() > 1) {
      run.reference_validation = std::move(answers[1].fits);
      for (ExperimentFit& fit : run.reference_validation) fit.trace = Trajectory();
      run.reference_check = CompareHeldOut(run.reference_validation, run.final_validation);
      run.reference_check.baseline = "reference";
    }
    if (!SetPredictionBands(config, model, v.experiments, options, &cache, &run, error)) {
      *error = "final validation: " + *error;
      return false;
    }
    if (config.velocity_validation && model.regression_form() != nullptr) {
      const RegressionDataOptions velocity_data = VelocityData(config, config.stages.size());
      std::vector<std::string> diverged;
      std::string why;
      if (!ValidateVelocities(config, model, v.experiments, velocity_data, final_values, &cache,
                              VelocitySteps{v.experiment.max_step, accepted_stages},
                              &run.final_velocity_validation, &diverged, &why, 0,
                              &run.final_held_out_parameters)) {
        run.final_velocity_validation.clear();
        diverged.clear();
        Finding skipped = SkippedVelocityCheck(why, "velocity_validation");
        skipped.stage = "final";
        run.findings.push_back(std::move(skipped));
      }
      for (const std::string& d : diverged) {
        Finding f = MakeFinding(FindingKind::kHeldOutDiverged, "velocity validation: " + d);
        f.stage = "final";
        run.findings.push_back(std::move(f));
      }
    }
  }
  FindManoeuvreRuns(config, &run, &cache);
  // What preparing the records did (what they say is diagnose/'s judgement).
  AddRecordNotes(config, cache, &run);
  run.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  *result = std::move(run);
  return result->stopped_stage.empty();
}

}  // namespace vesselid

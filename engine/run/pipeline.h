// A staged identification run (seed 002's hierarchy, generalised): stages run in order, each
// building its output-error problem from its experiments, its model restriction and its
// parameter roles. A parameter's start is its latest estimate unless the stage gives one;
// unlisted parameters are held there. After the last stage every parameter gets its final
// value: isolated and free ones from the last stage that estimated them, shared ones fused
// over all their stage estimates. Held-out experiments are simulated after each stage
// (local validation) and with the final values (final validation).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/config/config.h"
#include "engine/solve/progress.h"
#include "engine/regression/regression_data.h"
#include "engine/solve/stage.h"
#include "engine/step_regression/step_regression.h"

namespace vesselid {

// One estimated or fixed quantity of a stage as reported.
struct Estimate {
  std::string name;
  std::string kind;        // parameter or initial_state
  std::string role;        // free, fixed, per_experiment, isolated, shared
  std::string experiment;  // empty when shared
  double value = 0.0;
  double start = 0.0;
  double std_error = 0.0;  // NaN when fixed or undetermined
  double lower = 0.0, upper = 0.0;
  bool undetermined = false;  // part of a combination the stage's data do not determine
};

struct StageResult {
  std::string name;
  std::string model;  // the stage's model (restriction) name
  StageSummary summary;
  std::vector<Estimate> estimates;
  std::vector<std::string> correlation_names;  // free variables, matrix order
  Eigen::MatrixXd correlation;
  std::vector<std::string> admissibility;    // empty: M SPD, damping PSD (as the model checks)
  std::vector<ExperimentFit> validation;     // held-out experiments of the stage
  // Models with an equation-error form: one-step and free-run metrics of the regressed
  // states on the held-out experiments (velocity_validation.h).
  std::vector<ChannelMetrics> velocity_validation;
  // Step-regression stages: the samples, lasso paths and timings (step_regression.h).
  std::shared_ptr<const StepRegressionReport> step_regression;
};

// A parameter's estimate as a regression stage reports it: name, role and bounds from its
// spec, the value and standard error the stage found.
Estimate ParameterEstimate(const ParameterSpec& spec, double value, double std_error);

// A stage's parameter values in model order (a per-experiment one: its first experiment's).
std::vector<double> StageParameterValues(const ModelInfo& info, const StageResult& stage);

// A parameter's value after the whole run.
struct FinalParameter {
  std::string name;
  double value = 0.0;
  double std_error = 0.0;  // NaN when fixed or undetermined
  std::string role;        // role in the stages that estimated it; "fixed" if none did
  std::vector<std::string> stages;  // stages whose estimates make the value
  std::string rule;        // how: "stage", "inverse_variance", "mean" or "fixed"
  bool undetermined = false;
};

struct RunResult {
  std::vector<StageResult> stages;
  std::vector<FinalParameter> parameters;  // model parameter order
  std::vector<std::string> admissibility;  // of the final values
  std::vector<ExperimentFit> final_validation;
  std::vector<ChannelMetrics> final_velocity_validation;
  double time_seconds = 0.0;
};

// What a run tells as it goes (terminal progress, checkpoints). Any member may be empty.
struct RunObserver {
  std::function<void(size_t index, const std::string& stage)> stage_started;
  // After each stage, before the next starts; false (with `error`) stops the run.
  std::function<bool(size_t index, const StageResult& stage, std::string* error)> stage_finished;
  ProgressCallback progress;  // solver iterations and global evaluations of output-error stages
};

// Runs every stage. On failure nothing is returned but the message naming the stage and cause.
// `finished` resumes a run: the results of its first stages, as an earlier run of the same
// config and data produced them (checkpoint.h); the run goes on from the next stage.
bool RunIdentification(const RunConfig& config, RunResult* result, std::string* error,
                       const RunObserver& observer = {},
                       std::vector<StageResult> finished = {});

// The parameter specs stage `index` is solved with after stages [0, index) ran as a run
// runs them (starts carried, unlisted parameters held at their latest estimates); `before`
// (optional) receives the results of those it needed (the stages up to the last one that
// estimates a parameter stage `index` carries) and `solved` (optional) the stage's own, run as
// the run runs it (continuation, global start). Used by studies of one stage.
bool ResolveStage(const RunConfig& config, size_t index, std::vector<ParameterSpec>* specs,
                  std::vector<StageResult>* before, std::string* error,
                  StageResult* solved = nullptr);

// Held-out experiments with every parameter fixed at `values` (model order). Initial states
// come from the data, except `free_states`, which are estimated first with the parameters
// held (a decay test's unmeasured initial yaw rate, a segment's velocities), as a validation
// of the parameters, not of a guessed start. The problem at those states; null with `error`.
std::unique_ptr<OutputErrorProblem> HeldOutProblem(const ModelHandle& model,
                                                   std::vector<Experiment> experiments,
                                                   const std::vector<std::string>& free_states,
                                                   const LocalSolveOptions& local,
                                                   const std::vector<double>& values,
                                                   std::string* error);

// Recorded data by experiment, so that stages sharing an experiment read it once.
using TrajectoryCache = std::map<std::string, Trajectory>;

// Reads and prepares experiments for a model (used by RunIdentification and by tools); the
// model guesses initial states from the data (ModelHandle::GuessState). segment_length > 0
// cuts every record into segments no longer than that (continuation phases); 0 keeps each
// experiment's own segmentation.
bool PrepareExperiments(const RunConfig& config, const std::vector<std::string>& names,
                        const ModelHandle& model, const ExperimentOptions& options,
                        TrajectoryCache* cache, std::vector<Experiment>* experiments,
                        std::string* error, double segment_length = 0.0);

// The experiments a configured record is identified as: itself, its segments (segments
// column) or consecutive pieces no longer than segment_length (its own or the given one).
bool RecordSpecs(const ExperimentSpec& spec, const Trajectory& data, double segment_length,
                 std::vector<ExperimentSpec>* specs, std::string* error);

// Equation-error records of `names` (each segment its own record).
bool PrepareRegressionRecords(const RunConfig& config, const std::vector<std::string>& names,
                              const ModelHandle& model, const RegressionDataOptions& options,
                              TrajectoryCache* cache, std::vector<RegressionRecord>* records,
                              std::string* error);

}  // namespace vesselid

// What a staged run reports: per stage its estimates, correlations, fits and validation; after
// the last stage every parameter's final value. Plain data, written by output/ (results.json,
// report.txt, report.html) and archived by checkpoints; names become text only there.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/base/finding.h"
#include "engine/data/turning_figures.h"
#include "engine/data/zigzag_figures.h"
#include "engine/model/model.h"
#include "engine/run/disturbance_report.h"
#include "engine/run/selection_result.h"
#include "engine/solve/noise_weights.h"
#include "engine/solve/parameter.h"
#include "engine/solve/residual_analysis.h"
#include "engine/solve/stage.h"
#include "engine/step_regression/step_regression.h"

namespace vesselid {

// What an estimate is of: a model parameter, an experiment's initial state, or a parameter of
// the filter-error method's disturbance model (model/disturbance.h).
enum class EstimateKind { kParameter, kInitialState, kNoise };

const char* EstimateKindToString(EstimateKind kind);  // "parameter", "initial_state", "noise"
bool StringToEstimateKind(const std::string& text, EstimateKind* kind);

// A free run's drift from its record against what the identified disturbance lets it
// (free_run_drift.h): sums of squares over the experiment's samples of the output, model units.
// Observed / expected SSE up to which a free run's drift is the identified disturbance's (a
// random walk's 2 int_0^1 W^2 dt, mean 1, exceeds 8 with probability about 1 %).
inline constexpr double kDriftExplained = 8.0;
struct FreeRunDrift {
  std::string experiment, output;
  int samples = 0;
  double observed_sse = 0.0, expected_sse = 0.0;
  double ratio() const { return observed_sse / expected_sse; }
  bool explained() const { return ratio() <= kDriftExplained; }
};

// One estimated or fixed quantity of a stage as reported.
struct Estimate {
  std::string name;
  EstimateKind kind = EstimateKind::kParameter;
  ParameterRole role = ParameterRole::kFree;
  std::string experiment;  // empty when one value serves every experiment
  double value = 0.0;
  double start = 0.0;
  double std_error = 0.0;  // NaN when fixed or undetermined
  double lower = 0.0, upper = 0.0;
  bool undetermined = false;  // part of a combination the stage's data do not determine
};

// A stage's fit to its held-out experiments beside the fit of the values it started from:
// per compared output the MAE pooled over the held-out samples, and how many held-out runs
// diverged. `worse`: more runs diverged, or the mean MAE ratio stage / start exceeds
// kHeldOutTolerance.
struct HeldOutCheck {
  bool done = false;
  std::vector<std::string> outputs;
  std::vector<double> start_mae, stage_mae;
  int start_diverged = 0, stage_diverged = 0;
  // The start's MAE on the runs both simulate is more than twice the stage's (mean ratio of
  // the outputs below kStartFarWorse): more diverging runs do not make the stage worse.
  bool start_far_worse = false;
  bool worse = false;
  // What the stage is held against: "start" (its start values), or "previous" where the
  // previous stages' values, differing from the start (a stage that restarts a parameter from
  // the config), predict the held-out runs better: the better of the two is the guard. A stage
  // set aside against "previous" leaves those values to the next stage.
  std::string baseline = "start";
  // "its start" or "the previous stages' values", for messages.
  // "reference": the final validation against `final_validation.reference`.
  std::string BaselineText() const {
    if (baseline == "reference") return "the reference model";
    return baseline == "previous" ? "the previous stages' values" : "its start";
  }
};

inline constexpr double kHeldOutTolerance = 1.01;
inline constexpr double kStartFarWorse = 0.5;

// Per-experiment parameters (a rudder bias per run) on held-out runs (held_out.h). With
// `fitted` (per_experiment: fit) each held-out run estimates its own values together with its
// free initial states, the other parameters held; `estimates` holds them per run (name
// "delta_0[zz3]", experiment set), and `without` the same runs simulated with them held at
// their start, so that the report shows what they buy. Empty when the model run has none.
struct HeldOutParameters {
  bool fitted = false;
  std::vector<std::string> parameters;  // model names, e.g. delta_0
  std::vector<Estimate> estimates;
  std::vector<ExperimentFit> without;  // no traces
  bool active() const { return !parameters.empty(); }
};

struct StageResult {
  std::string name;
  std::string model;  // the stage's model (restriction) name
  StageSummary summary;
  std::vector<Estimate> estimates;
  std::vector<std::string> correlation_names;  // free variables, matrix order
  Eigen::MatrixXd correlation;
  std::vector<std::string> admissibility;  // empty: M SPD, damping PSD (as the model checks)
  std::vector<ExperimentFit> validation;   // held-out experiments of the stage
  HeldOutCheck held_out;                   // validation against the stage's start values
  HeldOutParameters held_out_parameters;   // per-experiment parameters of `validation`
  // > 0: the integration step the stage was solved with, shorter than the configured one
  // because its estimate's dynamics were too fast for that (step_stability.h).
  double integration_step = 0.0;
  // Output-error stages: the per-channel noise model under `weights: noise` (its sigmas
  // weigh the samples and make the covariance), else method "given" (noise_weights.h).
  NoiseModel noise_model;
  // Non-empty: why the run set the stage's estimates aside (final: best_validation); later
  // stages and the final values take its start values instead.
  std::string rejected;
  // Models with an equation-error form: one-step and free-run metrics of the regressed
  // states on the held-out experiments (velocity_validation.h).
  std::vector<ChannelMetrics> velocity_validation;
  // Output-error stages: whiteness of the fit's residuals and their correlation with the
  // inputs, per experiment and compared output (residual_analysis.h).
  std::vector<ResidualAnalysis> residuals;
  std::vector<ResidualAnalysis> validation_residuals;  // of `validation`, reported only
  // Filter-error stages: the disturbance model, auto's candidates, the held-out predictions
  // through the filter (disturbance_report.h).
  DisturbanceReport disturbance;
  // Filter-error stages with process noise: how far each free run drifted against how far
  // the identified disturbance lets it (free_run_drift.h).
  std::vector<FreeRunDrift> free_run_drift;
  // The cost at the estimate with every channel weighted as configured (weights: fixed for
  // the stage whatever the noise model did), so that end points from other starts, runs
  // and tools rank by it; the minimised cost under `weights: noise` is ~N/2 at any end point.
  // NaN where not computed (regression stages: their cost is the regression's).
  double comparable_cost = std::numeric_limits<double>::quiet_NaN();
  // Output-error stages: the operating range of the stage's records (operating_range.h: per
  // state the largest |x| the simulation reaches at the estimate, per input its smallest and
  // largest value), over which admissibility is judged (ModelHandle::Admissibility); empty
  // elsewhere (judged for every value).
  std::vector<double> state_limits;
  // ModelHandle::StructureDoubts at the stage's estimate over that range.
  std::vector<std::string> structure_doubts;
  // What the stage's judgement found (diagnose/) and the verdict they make.
  std::vector<Finding> findings;
  Verdict verdict = Verdict::kGood;
  // Step-regression stages: the samples, lasso paths and timings (step_regression.h).
  std::shared_ptr<const StepRegressionReport> step_regression;
  // Regression stages: bootstrap over the CV groups (group_bootstrap.h); runs 0: none.
  BootstrapSummary bootstrap;
};

// A parameter's estimate as a regression stage reports it: name, role and bounds from its
// spec, the value and standard error the stage found.
Estimate ParameterEstimate(const ParameterSpec& spec, double value, double std_error);

// A stage's parameter values in model order, one per model parameter: a per-experiment one
// is the mean over the stage's experiments (a held-out run has no value of its own); one the
// stage does not report, the model's default.
std::vector<double> StageParameterValues(const ModelInfo& info, const StageResult& stage);

// A parameter's value after the whole run.
struct FinalParameter {
  std::string name;
  double value = 0.0;
  double std_error = 0.0;  // NaN when fixed or undetermined
  // Role in the last stage that estimated it; kFixed if none did.
  ParameterRole role = ParameterRole::kFixed;
  std::vector<std::string> stages;  // stages whose estimates make the value
  std::string rule;  // how: "stage", "inverse_variance", "mean", "fixed" (fusion.h) or
                     // "per_experiment"
  bool undetermined = false;
  // Role per_experiment: one value per run in the last stage that estimated it; `value` is
  // then their mean, what a run without a value of its own is simulated with (held-out runs,
  // predict, the exported model and FMU, Python's model).
  int runs = 0;
  double runs_min = std::numeric_limits<double>::quiet_NaN();
  double runs_max = std::numeric_limits<double>::quiet_NaN();
};

// A zigzag among the run's simulated records (manoeuvre_runs.h): the test as the record flies
// it and its figures, measured and simulated.
struct ZigzagRun {
  std::string stage;  // the stage whose fit it is, or "final" (final validation)
  std::string experiment;
  bool held_out = false;
  ZigzagTest test;
  ZigzagFigures measured, simulated;
  // A held-out run flown from its measured start, re-flown in closed loop as the test was
  // flown (run/zigzag_reflight.h: the rudder reversed at the model's own checks); where it
  // could not be, `reflown_why` says why.
  bool reflown_done = false;
  ZigzagFigures reflown;
  std::string reflown_why;
};

// A turning circle among the run's simulated records (manoeuvre_runs.h): the test as the record
// flies it and its figures, measured on the recorded track and on the simulated one.
struct TurningRun {
  std::string stage;  // the stage whose fit it is, or "final" (final validation)
  std::string experiment;
  bool held_out = false;
  std::string unit;  // the track's unit ("m")
  TurningTest test;
  TurningFigures measured, simulated;
};

// Where a record's relative times and local positions start (record_notes.h).
struct RecordOrigin {
  std::string experiment;
  bool epoch = false;  // t = 0 at the Unix time time_origin_ns
  std::int64_t time_origin_ns = 0;
  bool position = false;  // north/east from GNSS fixes, 0 at lat, lon (degrees)
  double lat = 0.0, lon = 0.0;
};

struct RunResult {
  std::vector<StageResult> stages;  // the finished ones
  // What the run found about its records and its final values (diagnose/), each naming the
  // stage, parameter or experiment, and the run's verdict: printed on stderr and first in
  // every output. Stage findings are in each StageResult.
  std::vector<Finding> findings;
  Verdict verdict = Verdict::kGood;
  // Set when the run stopped before its last stage: the stage it stopped in and why.
  std::string stopped_stage, stop_message;
  std::vector<FinalParameter> parameters;  // model parameter order
  std::vector<std::string> admissibility;  // of the final values
  std::vector<std::string> structure_doubts;  // ModelHandle::StructureDoubts of the final values
  std::vector<ExperimentFit> final_validation;
  std::vector<ResidualAnalysis> final_validation_residuals;  // reported only
  HeldOutParameters final_held_out_parameters;  // per-experiment parameters of final_validation
  // With `final_validation.reference`: the reference model's fits of the same runs (no
  // traces), and the final values held against them (baseline "reference").
  std::vector<ExperimentFit> reference_validation;
  HeldOutCheck reference_check;
  std::vector<ChannelMetrics> final_velocity_validation;
  std::vector<ZigzagRun> zigzags;  // every zigzag fit of the stages and the final validation
  std::vector<TurningRun> turning_circles;  // every turning circle fit, likewise
  // Set by `vesselid select` on the chosen candidate's run: the structure selection that
  // chose it (selection_result.h); null for a plain run.
  std::shared_ptr<const SelectionResult> selection;
  std::vector<RecordOrigin> record_origins;
  double time_seconds = 0.0;
};

}  // namespace vesselid

// Held-out experiments simulated with the parameters fixed: a stage's validation and the
// run's final validation. A held-out run is a prediction (HeldOutStart, run_config.h): the
// states its record measures start at their measured values; of `free_states` those it does
// not measure (a decay test's yaw rate, a ship's velocities) are estimated on a burn-in at
// its start with the parameters held, and the fit is scored after the burn-in. Asked for
// (`held_out: {start: refitted}`), every free state is estimated on the whole run instead,
// and the figures from the measured start are reported beside it.
//
// Per-experiment parameters (a rudder bias per run) have no value for a held-out run. With
// HeldOutPerExperiment::kFit each run estimates its own, with its free states, the shared
// parameters held (min over b_e, x0_e of the run's cost at the shared values); the run is also
// simulated with them held at their start (the fit "without"), so that the report shows what
// they buy. With kHold they are held at their start.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/display_units.h"
#include "engine/run/run_result.h"
#include "engine/solve/local_solve.h"
#include "engine/solve/metrics.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/residual_analysis.h"

namespace vesselid {

// The problem of `experiments` with every parameter fixed at `values` (model order) except
// `per_experiment` (role per_experiment, start and bounds as given), at its estimated free
// states and per-experiment values (solved with `local`, to tolerances no tighter than 1e-8
// in cost and step); null with `error`.
std::unique_ptr<OutputErrorProblem> HeldOutProblem(
    const ModelHandle& model, std::vector<Experiment> experiments,
    const std::vector<std::string>& free_states, const LocalSolveOptions& local,
    const std::vector<double>& values, std::string* error,
    const std::vector<ParameterSpec>& per_experiment = {}, const InitialStatePrior& prior = {});

// What held-out runs do with the per-experiment parameters of the stage (or of the last stage
// that had them): `parameters` with their start (the value held, and the fit "without") and
// bounds; `fit_start` (same order) where each run's estimate starts, e.g. the stage's mean.
//
// From the measured start a run's own parameters are estimated on its burn-in, which may say
// little of them (a rudder bias from the first 9 s of a zigzag): the estimate b (standard
// error se) is combined with the training runs' values (mean m, SD s) as a normal prior would,
//   b' = (b / se^2 + m / s^2) / (1 / se^2 + 1 / s^2),  se' = (1 / se^2 + 1 / s^2)^-1/2,
// so that a run predicts no worse than the training mean where its burn-in cannot tell.
struct HeldOutPerRun {
  HeldOutPerExperiment mode = HeldOutPerExperiment::kFit;
  std::vector<ParameterSpec> parameters;
  std::vector<double> fit_start;
  std::vector<double> spread;  // SD of the training runs' values (NaN with fewer than two)
};

// The per-experiment parameters of the estimates of `stage` that `model` has: bounds as the
// stage had them; held ("without") at, and fitted from, the mean of the stage's estimates.
HeldOutPerRun PerRunFromStage(const StageResult& stage, const ModelInfo& model,
                              HeldOutPerExperiment mode);

// Prepares the records `names` and fits them as HeldOutProblem does, into `fits` (and, with
// per-experiment parameters, their estimates and the fits without them into `parameters`;
// may be null when there are none). A record whose free run diverges, or whose initial states
// cannot be estimated, is recorded as diverged with the reason (ExperimentFit::diverged);
// false only when the records cannot be prepared. With `residuals`, the residual analysis of
// each run's fit (fit_residuals.h) goes there.
bool SimulateHeldOut(const RunConfig& config, const ModelHandle& model,
                     const std::vector<std::string>& names, const ExperimentOptions& options,
                     const std::vector<std::string>& free_states, const LocalSolveOptions& local,
                     const std::vector<double>& values, TrajectoryCache* cache,
                     std::vector<ExperimentFit>* fits, std::string* error,
                     const HeldOutPerRun& per_run = {}, HeldOutParameters* parameters = nullptr,
                     std::vector<ResidualAnalysis>* residuals = nullptr,
                     const HeldOutStart& start = {});

// One set of parameter values (model order) at which SimulateHeldOutPasses fits the held-out
// runs, and where that pass's fits go. With `parameters` null the fits "without" the
// per-experiment parameters are not run; `residuals` may be null.
struct HeldOutPass {
  const std::vector<double>* values = nullptr;
  std::vector<ExperimentFit>* fits = nullptr;
  HeldOutParameters* parameters = nullptr;
  std::vector<ResidualAnalysis>* residuals = nullptr;
};

// SimulateHeldOut at several sets of values at once (a stage's estimate and its start): the
// records are prepared once and every fit of every pass runs in one parallel batch.
bool SimulateHeldOutPasses(const RunConfig& config, const ModelHandle& model,
                           const std::vector<std::string>& names, const ExperimentOptions& options,
                           const std::vector<std::string>& free_states,
                           const LocalSolveOptions& local, const std::vector<HeldOutPass>& passes,
                           TrajectoryCache* cache, std::string* error,
                           const HeldOutPerRun& per_run = {}, const HeldOutStart& start = {});

// Notes on held-out per-experiment estimates at a bound ("validation: delta_0[zz3] is at its
// upper bound 0.05 ..."), as the stage notes active bounds.
std::vector<std::string> HeldOutBoundNotes(const HeldOutParameters& parameters);

// The mean over the outputs of stage MAE / start MAE (outputs whose start MAE is above 0);
// NaN where there is none.
double MeanMaeRatio(const HeldOutCheck& check);

// Whether fits `a` predict the held-out runs better than fits `b`: no more runs diverge, and
// the pooled MAE is lower on the runs both simulate (mean ratio over the outputs below 1).
bool PredictsBetter(const std::vector<ExperimentFit>& a, const std::vector<ExperimentFit>& b);

// The held-out check of a stage from its fits and those of its start values (HeldOutCheck).
HeldOutCheck CompareHeldOut(const std::vector<ExperimentFit>& start,
                            const std::vector<ExperimentFit>& stage);

// "worse on held-out data than its start: MAE psi 0.01 -> 0.03, ...", each output's MAE in
// the unit `unit_of` gives it (empty: the model's; the record the unit is judged on is
// `experiment`, a held-out run).
// The final validation against a reference model (RunResult::reference_check), with the runs
// each diverged on, in the units `unit_of` gives the first held-out run: "held-out MAE psi
// 0.14 -> 0.22 deg; the reference diverged on 2 of 2 runs".
std::string DescribeReferenceCheck(const RunResult& run, const DisplayUnitOf& unit_of = {});

std::string DescribeHeldOut(const HeldOutCheck& check, const DisplayUnitOf& unit_of = {},
                            const std::string& experiment = "");

}  // namespace vesselid

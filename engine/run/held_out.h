// Held-out experiments simulated with every parameter fixed: a stage's validation and the
// run's final validation. Initial states come from the data, except `free_states`, which are
// estimated first with the parameters held (a decay test's unmeasured initial yaw rate, a
// segment's velocities), as a validation of the parameters, not of a guessed start.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/local_solve.h"
#include "engine/solve/metrics.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

// The problem of `experiments` with every parameter fixed at `values` (model order), at its
// estimated free states; null with `error`.
std::unique_ptr<OutputErrorProblem> HeldOutProblem(const ModelHandle& model,
                                                   std::vector<Experiment> experiments,
                                                   const std::vector<std::string>& free_states,
                                                   const LocalSolveOptions& local,
                                                   const std::vector<double>& values,
                                                   std::string* error);

// Prepares the records `names` and fits them as HeldOutProblem does, into `fits`. A record
// whose free run diverges, or whose initial states cannot be estimated, is recorded as
// diverged with the reason (ExperimentFit::diverged); false only when the records cannot be
// prepared.
bool SimulateHeldOut(const RunConfig& config, const ModelHandle& model,
                     const std::vector<std::string>& names, const ExperimentOptions& options,
                     const std::vector<std::string>& free_states, const LocalSolveOptions& local,
                     const std::vector<double>& values, TrajectoryCache* cache,
                     std::vector<ExperimentFit>* fits, std::string* error);

// The held-out check of a stage from its fits and those of its start values (HeldOutCheck).
HeldOutCheck CompareHeldOut(const std::vector<ExperimentFit>& start,
                            const std::vector<ExperimentFit>& stage);

// "worse on held-out data than its start: MAE psi 0.01 -> 0.03, ...".
std::string DescribeHeldOut(const HeldOutCheck& check);

}  // namespace vesselid

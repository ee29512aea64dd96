// The prediction band of the final validation's held-out runs (PredictionBand, metrics.h):
// whether each run, flown from its measured start, is predicted as well as the training fit
// and the uncertainty of the estimates lead one to expect.
//
// With r the run's scored residuals (simulated minus measured), S their sensitivities to the
// estimated parameters and to the run's initial state (and its own per-experiment
// parameters), sigma_o^2 the training fit's mean square residual of output o, and P the
// covariance of all of these (the estimates' standard errors and correlations; a measured
// state's start its noise variance, an estimated one the data's guess of it, a run's own
// parameter its burn-in estimate's), the held-out error is what no adjustment within P
// explains:
//   Q = min_d  |r - S d|^2_sigma + d' P^-1 d
//     = |r|^2_sigma - b' (I + L' S' S L / sigma^2)^-1 b,   b = L' S' r / sigma^2,  P = L L'.
// For a correct model with honest intervals Q is about the number of scored samples; a
// structure that fits its training run and misses the next one (a speed loss the model
// has not, a nonlinearity a zigzag of another size shows) leaves Q many times that.
#pragma once

#include <string>
#include <vector>

#include "engine/model/model_handle.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// Sets `band` of every fit of run->final_validation flown from its measured start (the runs
// of the configured `records`), from the last accepted output-error stage's fit and
// run->parameters. Runs that diverged, were refitted, or whose outputs the training fit did
// not compare are left without. False with `error` only when the records cannot be prepared.
bool SetPredictionBands(const RunConfig& config, const ModelHandle& model,
                        const std::vector<std::string>& records, const ExperimentOptions& options,
                        TrajectoryCache* cache, RunResult* run, std::string* error);

}  // namespace vesselid

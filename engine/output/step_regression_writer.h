// Outputs of step-regression stages and of damping-inertia models, beside results.json:
//
//   <stage>.damping_samples.csv     x, sigma, weight, group, turns, mirrored (seed Fig. 5)
//   <stage>.inertia_samples.csv     term, x, m, k, T, fit rms, group, mirrored (seed Fig. 7)
//   <stage>.lasso_<term>.csv        the lasso path: lambda, LOO-CV error and SE, nonzero,
//                                   normalised coefficients
//   <stage>.asymptote_<term>.csv    LOO-CV error over the (a, b) grid of an inertia term
//   surfaces/<stage>.csv, final.csv sigma and m on the configured grid (seed Figs. 8-9)
#pragma once

#include <string>
#include <vector>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// Per term: samples, normalisation, chosen lambda (and a, b), CV error, R2; the timings.
nlohmann::json StepRegressionToJson(const StepRegressionReport& report);

// The files above for every step-regression stage and, with config.surfaces, every stage's
// and the final surfaces. Each file is written atomically.
bool WriteStepRegressionFiles(const RunConfig& config, const RunResult& result,
                              const std::string& out_dir, std::string* error);

}  // namespace vesselid

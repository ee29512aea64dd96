// Monte Carlo noise study of one output-error stage: does the identification recover the
// truth, and are its reported intervals honest?
//
// The stage's experiments are simulated once with the truth (inputs and initial states as
// recorded), then for run r = 0..N-1 Gaussian noise N(0, sigma_c^2) seeded by (seed, r) is
// added to every sample of output c and the stage is identified as configured. Per free
// parameter, over the usable runs:
//   bias = mean(theta^) - theta*,  SD of theta^,  RMSE,  mean reported SE / SD,
//   coverage = share of runs with |theta^ - theta*| <= z se  (z = 1.96 for 95 %),
// with the binomial standard error of the coverage sqrt(c (1 - c) / N).
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/study/study_options.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// On rank 0 `result` holds {options, parameters, cases, summary}; other ranks get null.
// False (with `error`) for bad options or data; failed runs are counted, not fatal.
bool RunMonteCarloStudy(const RunConfig& config, const MonteCarloOptions& options,
                        unsigned seed, const CaseOptions& execution, nlohmann::json* result,
                        std::string* error, const CaseProgress& progress = nullptr);

std::string MonteCarloText(const nlohmann::json& result);

}  // namespace vesselid

// Monte Carlo noise study of one output-error stage: does the identification recover the
// truth, and are its reported intervals honest?
//
// The stage's experiments are simulated once with the truth (inputs and initial states as
// recorded), then for run r = 0..N-1 Gaussian noise seeded by (seed, r) is added to every
// sample of each output and to every logged sample of each noisy input (the experiments then
// rebuilt as the stage builds them: errors in variables, monte_carlo_noise.h), and the stage
// is identified as configured (its weights, input treatment and uncertainty method). The
// summary per free parameter is monte_carlo_summary.h's, with notes on what is doubtful.
//
// truth: estimate makes it a parametric bootstrap for data without a known truth: the stage
// is solved on the data first and its estimate (parameters, per-experiment values, initial
// states) is the truth; outputs whose noise is not given take the fit's residual SD. The
// bias is then the method's bias at the estimate, and the bootstrap SD stands beside the
// stage's reported SE.
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/study/study_options.h"
#include "engine/study/study_runner.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// On rank 0 `result` holds {options, parameters, cases, summary}; other ranks get null.
// False (with `error`) for bad options or data; failed runs are counted, not fatal.
bool RunMonteCarloStudy(const RunConfig& config, const MonteCarloOptions& options,
                        unsigned seed, const CaseOptions& execution, nlohmann::json* result,
                        std::string* error, const CaseProgress& progress = nullptr);

std::string MonteCarloText(const nlohmann::json& result);

}  // namespace vesselid

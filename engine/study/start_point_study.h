// Start-point study of one output-error stage: how often does the solver find the best
// optimum from an arbitrary start, with and without the global start?
//
// Start r = 0..N-1 draws every free parameter uniformly (or log-uniformly) in its bounds,
// seeded by (seed, r). Case r solves the stage locally from that start only; case N + r
// solves it from the same start with the global start first (its NLopt seed drawn from the
// same pair). The optima found are grouped: two are the same when every free parameter
// agrees within tolerance * max(|value|, scale). The lowest-cost group is "the best";
// reported per mode: fraction of starts reaching it, the distinct optima with their costs
// and counts, the spread of the estimates, evaluations and time.
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/study/study_options.h"
#include "engine/study/study_runner.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// On rank 0 `result` holds {options, parameters, optima, modes, cases}; other ranks: null.
bool RunStartPointStudy(const RunConfig& config, const StartPointOptions& options,
                        unsigned seed, const CaseOptions& execution, nlohmann::json* result,
                        std::string* error, const CaseProgress& progress = nullptr);

std::string StartPointText(const nlohmann::json& result);

}  // namespace vesselid

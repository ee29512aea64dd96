// results.json of a run: every estimate with value, standard error, bounds and role; per
// stage the global start, refinements, cost, notes, correlations, local analysis, fit and
// validation metrics; the final parameters and validation. Non-finite numbers are null.
#pragma once

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

nlohmann::json RunResultToJson(const RunConfig& config, const RunResult& result);

}  // namespace vesselid

// report.txt of a run: per stage the parameter table, notes, strongest correlations, local
// analysis and fit metrics; then the final parameters and validation.
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

std::string RunResultToText(const RunConfig& config, const RunResult& result);

}  // namespace vesselid

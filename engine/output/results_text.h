// report.txt of a run, read top-down: a summary first (the final parameters with their 95 %
// intervals, bounds flagged, counts; the fit per run of the last kept stage and of the final
// validation; the verdict and every finding), then per stage the parameter table, notes, strongest
// correlations, local analysis and the fit per run (run_fit_table.h); then the final
// validation.
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

std::string RunResultToText(const RunConfig& config, const RunResult& result);

}  // namespace vesselid

// Writing a run's outputs: results.json (every estimate with value, standard error, bounds,
// role; per-stage cost, iterations, time, notes; metrics per experiment and channel),
// traces/<stage>.<experiment>.csv (measured vs simulated outputs) and report.txt.
// Everything is formed in memory first and each file is written to a temporary name and
// renamed, results.json last, so a failed run never leaves a partial results file.
#pragma once

#include <string>

#include "engine/config/config.h"
#include "engine/run/pipeline.h"
#include "nlohmann/json.hpp"

namespace vesselid {

nlohmann::json RunResultToJson(const RunConfig& config, const RunResult& result);

// The human-readable report: per stage, the parameter table and fit metrics.
std::string RunResultToText(const RunConfig& config, const RunResult& result);

bool WriteRunResults(const RunConfig& config, const RunResult& result, const std::string& out_dir,
                     std::string* error);

// Writes `content` to path via a temporary file and rename.
bool WriteFileAtomically(const std::string& path, const std::string& content, std::string* error);

}  // namespace vesselid

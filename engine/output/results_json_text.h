// results.json's text for a run, for callers that do not handle JSON themselves (the public
// API's; results_json.h has the document).
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// Indented by `indent` spaces as `vesselid run` writes it (2, without the final newline), or
// compact with -1.
std::string RunResultJsonText(const RunConfig& config, const RunResult& result, int indent = 2);

}  // namespace vesselid

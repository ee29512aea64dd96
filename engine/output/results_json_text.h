// results.json's text for a run, for callers that do not handle JSON themselves (the public
// API's; results_json.h has the document).
#pragma once

#include <ostream>
#include <string>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// Indented by `indent` spaces as `vesselid run` writes it (2, without the final newline), or
// compact with -1.
std::string RunResultJsonText(const RunConfig& config, const RunResult& result, int indent = 2);

// The same text written to `out` as it is formed: the per-experiment arrays (estimates, fit
// metrics, residual analyses) an element at a time, never the whole document in memory
// (json_splices.h).
void WriteRunResultJson(const RunConfig& config, const RunResult& result, int indent,
                        std::ostream* out);

}  // namespace vesselid

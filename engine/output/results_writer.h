// Writing a run's outputs into its folder: traces/<stage>.<experiment>.csv (measured vs
// simulated outputs), the step-regression files, report.txt (results_text.h), report.html
// (report_html.h) and results.json (results_json.h). Everything is formed in memory first and
// each file is written to a temporary name and renamed, results.json last, so a failed run
// never leaves a partial results file.
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

bool WriteRunResults(const RunConfig& config, const RunResult& result, const std::string& out_dir,
                     std::string* error);

}  // namespace vesselid

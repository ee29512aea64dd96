// Writing a run's outputs into its folder: traces/<stage>.<experiment>.csv (measured vs
// simulated outputs), the step-regression files, report.txt (results_text.h), report.html
// (report_html.h) and results.json (results_json.h). Everything is formed in memory first and
// each file is written to a temporary name and renamed, results.json last, so a failed run
// never leaves a partial results file. Without `html_report` (`vesselid run --no-report`, batch
// use) report.html and its plots are not formed, and an earlier run's report.html in the folder
// is removed so that it cannot be mistaken for this run's.
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

bool WriteRunResults(const RunConfig& config, const RunResult& result, const std::string& out_dir,
                     std::string* error, bool html_report = true);

}  // namespace vesselid

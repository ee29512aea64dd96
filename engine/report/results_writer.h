// Writing a run's outputs into its folder: traces/<stage>.<experiment>.csv (measured vs
// simulated outputs), the step-regression files, report.txt (results_text.h), report.html
// (report_html.h) and results.json (results_json.h). Everything is written into the folder's
// staging folder first and published as one set, results.json last (output_staging.h): a run
// that fails while writing (a full disk, a name, a stop request) leaves the previous set
// whole, and a folder with results.json holds one whole set. Without `html_report`
// (`vesselid run --no-report`, batch use) report.html and its plots are not formed, and an
// earlier run's report.html leaves the folder with the rest of the earlier set. With
// `with_checkpoint` (`vesselid run`) the run's working checkpoint is published with them as
// checkpoint/ (checkpoint.h).
#pragma once

#include <string>
#include <vector>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

bool WriteRunResults(const RunConfig& config, const RunResult& result, const std::string& out_dir,
                     std::string* error, bool html_report = true,
                     bool with_checkpoint = false);

}  // namespace vesselid

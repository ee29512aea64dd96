// The run report, report.html: one self-contained page (no network: styles and script inline,
// plots embedded as data: URIs of SVGs drawn by gnuplot, report_figures.h).
//
//   summary     final parameters (clipped intervals, bounds flagged, counts, fusion notes),
//               fit per run (sortable, worst first when long, mean / median / worst), every
//               finding (report_summary.h)
//   per stage   summary (cost, iterations, termination, time, notes); measured vs simulated
//               outputs and residuals in the data's units, a figure per record of the stage's
//               fit (its segments end to end, each on its own time axis) with metrics, and its
//               x-y track where the model has horizontal positions; the counts of unknowns;
//               the estimates; the correlation heat map of the shared parameters
//               (per-experiment unknowns left out); the cost history; validation
//               figures of held-out records; step-regression tables, lasso CV paths and samples
//   final       admissibility, final validation figures and metrics
//   papers      parameters by stage, cost per test, validation fit %
//
// Every plot is `<img class="plot" data-plot="<key>">`; once the page has loaded, a script
// writes the number that rendered and the total to body data-plots-loaded / data-plots-total.
// Without gnuplot the page still has every table, and a notice says why plots are missing.
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// Writes out_dir/report.html atomically. False only when the file cannot be written.
bool WriteRunReport(const RunConfig& config, const RunResult& result, const std::string& out_dir,
                    std::string* error);

// The page itself, for WriteRunReport and tests.
std::string RunReportHtml(const RunConfig& config, const RunResult& result);

}  // namespace vesselid

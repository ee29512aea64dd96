// The summary that opens report.html, for a marine engineer reading top-down: the final
// parameters with their 95 % intervals (clipped to the bounds and flagged, a parameter on its
// bound marked), the counts of unknowns (parameters by role, initial states apart), why a fused
// value lies outside its stages' estimates, the fit per run of the last kept stage and of the
// final validation, the verdict and every finding. Other sections plug in after it (report_html.h).
#pragma once

#include <string>

#include "engine/output/run_fit_table.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// One row per run, sortable by any column (a click on its heading); the mean, median and
// worst rows below, labelled, kept out of the sort.
std::string RunFitTableHtml(const RunFitTable& table);

// Final parameters: unit, value, standard error, clipped 95 % interval, bounds, flags, role,
// stages and rule, in the unit the data came in (shown_parameters.h); a fixed parameter's row
// muted.
std::string FinalParametersSummaryHtml(const RunConfig& config, const RunResult& result);

// The whole summary section (id "summary").
std::string SummarySectionHtml(const RunConfig& config, const RunResult& result);

// The script that sorts table.sortable by a clicked heading (numbers as numbers).
extern const char kSortScript[];

}  // namespace vesselid

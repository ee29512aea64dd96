// HTML tables of the run report (report_html.h): metrics, estimates, velocity validation,
// step regression, and the tables the identification papers print (the final parameters:
// report_summary.h).
// Every name is HTML-escaped; unknown numbers (NaN) print as a dash.
#pragma once

#include <string>
#include <vector>

#include "engine/output/run_fit_table.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/metrics.h"
#include "engine/step_regression/step_regression.h"

namespace vesselid {

// &, <, >, " and ' as character references.
std::string HtmlEscape(const std::string& text);

// printf-formatted number, or a dash when it is not finite.
std::string HtmlNumber(double value, const char* format = "%.6g");

// Fits grouped by record, in order of first appearance.
std::vector<std::vector<const ExperimentFit*>> GroupByRecord(
    const std::vector<ExperimentFit>& fits);


// Per experiment and channel: samples, RMSE, MAE, R2, fit %, and the experiment's
// sqrt(mean e^2); with a config, RMSE and MAE in the unit the user reads, named in a column
// (display_units.h).
std::string MetricsTable(const std::vector<const ExperimentFit*>& fits,
                         const RunConfig* config = nullptr);

// A stage's estimates: the estimated shared ones, per-experiment ones (parameters and initial
// states) and the ones held fixed, each with value, standard error, 95 % interval, start and
// bounds; with a config in the unit the data came in (shown_parameters.h), named in a column.
std::string EstimatesTables(const std::vector<Estimate>& estimates,
                            const RunConfig* config = nullptr);

// One-step and free-run metrics of the regressed states (velocity_validation.h).
std::string VelocityTable(const std::vector<ChannelMetrics>& metrics);

// Per regressed term: chosen lambda, a, b, CV error, R2, samples, groups; the sample counts.
std::string StepRegressionTables(const StepRegressionReport& report);

// (a) parameters by stage with the final value and rule, (b) per-test cost and fit % of the
// identification fits, (c) validation fit % per held-out experiment and output, per stage and
// final.
std::string PaperTables(const RunConfig& config, const RunResult& result);

}  // namespace vesselid

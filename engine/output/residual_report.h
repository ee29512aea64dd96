// The residual analysis of a stage (residual_analysis.h) as results.json, report.txt and
// report.html show it: per experiment and output the autocorrelation with its band, the
// Ljung-Box test and the cross-correlation with each input; in the text one line per channel,
// or a count per output and the coloured ones named when there are many segments; the HTML
// in report/residual_html.h.
#pragma once

#include <string>
#include <vector>

#include "engine/output/json_splices.h"
#include "engine/solve/residual_analysis.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// [{experiment, output, samples, lags, autocorrelation, band_99, band_95,
//   ljung_box: {q, dof, p}, lag1, white, cross_correlation: {<input>: {lags, values, band_99,
//   correlated}}, input_correlated, interval_spread, irregular_sampling}]; with `splices`
// its placeholder there (json_splices.h).
nlohmann::json ResidualAnalysesToJson(const std::vector<ResidualAnalysis>& analyses,
                                      JsonSplices* splices = nullptr);

// Channels worst first: coloured (largest |lag-1| first), then input-correlated, then white,
// then untested.
std::vector<const ResidualAnalysis*> ResidualsWorstFirst(
    const std::vector<ResidualAnalysis>& analyses);

// Lines "<indent>residuals run2 psi: coloured (lag-1 0.93, Ljung-Box p < 1e-16)"; above
// kResidualLinesMax channels of an output, "<indent>residuals psi: 87 of 89 experiments
// white; coloured: ..." with the worst six named.
inline constexpr size_t kResidualLinesMax = 8;
std::string ResidualAnalysesText(const std::vector<ResidualAnalysis>& analyses,
                                 const std::string& indent);

}  // namespace vesselid

// The residual analysis of a stage (residual_analysis.h) as results.json, report.txt and
// report.html show it: per experiment and output the autocorrelation with its band, the
// Ljung-Box test and the cross-correlation with each input; in the text one line per channel,
// or a count per output and the coloured ones named when there are many segments; in the
// HTML a table and MATLAB resid's two plots for the worst channels.
#pragma once

#include <string>
#include <vector>

#include "engine/output/report_figures.h"
#include "engine/solve/residual_analysis.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// [{experiment, output, samples, lags, autocorrelation, band_99, band_95,
//   ljung_box: {q, dof, p}, lag1, white, cross_correlation: {<input>: {lags, values, band_99,
//   correlated}}, input_correlated, interval_spread, irregular_sampling}]
nlohmann::json ResidualAnalysesToJson(const std::vector<ResidualAnalysis>& analyses);

// Lines "<indent>residuals run2 psi: coloured (lag-1 0.93, Ljung-Box p < 1e-16)"; above
// kResidualLinesMax channels of an output, "<indent>residuals psi: 87 of 89 experiments
// white; coloured: ..." with the worst six named.
inline constexpr size_t kResidualLinesMax = 8;
std::string ResidualAnalysesText(const std::vector<ResidualAnalysis>& analyses,
                                 const std::string& indent);

// The channels worth plotting, worst first: coloured (largest |lag-1|), then input-correlated,
// then the rest, at most `count`.
std::vector<const ResidualAnalysis*> ResidualsToPlot(const std::vector<ResidualAnalysis>& analyses,
                                                     size_t count);

// MATLAB resid's figure of one channel: the autocorrelation r_1..r_L with its 99 % band on
// top, below it the cross-correlation with each input at lags -L..L with its band. False when
// the channel was not tested.
bool ResidualFigure(const std::string& name, const ResidualAnalysis& analysis, Figure* figure);

// A summary line and a table of the channels (sortable; all of them up to 40 rows, else the
// 40 worst), verdicts flagged.
std::string ResidualTableHtml(const std::vector<ResidualAnalysis>& analyses);

}  // namespace vesselid

// The residual analysis of a stage (output/residual_report.h) as report.html shows it: a
// table of the channels and MATLAB resid's two plots for the worst ones.
#pragma once

#include <string>
#include <vector>

#include "engine/report/report_figures.h"
#include "engine/solve/residual_analysis.h"

namespace vesselid {

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

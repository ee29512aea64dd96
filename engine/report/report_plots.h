// The figure types of the HTML report (report_html.h) as gnuplot figures (report_figures.h):
//
//   trace        measured vs simulated outputs of one record, a row per output channel, in
//                the units the user reads (display_units.h, labels "psi [deg]"): the
//                signals, and the residual e = measured - simulated (angles wrapped to
//                (-pi, pi], and a simulated angle drawn on the measured one's branch,
//                y + wrap(y_sim - y)); each series min/max-decimated to about two points per
//                pixel column of its panel (kSignalPoints, kResidualPoints); the segments of
//                a record end to end, each on its own time axis (t - its start), so that a
//                few minutes of segments in a long log are not slivers on its absolute axis
//   track        the x-y track: north against east, measured and simulated, equal scales
//   correlation  heat map of a correlation matrix, palette -1 (blue) .. 1 (red), values printed
//                in the cells of matrices up to 12 x 12
//   cost         cost per Ceres iteration of every refinement of a stage (log y), the chosen
//                one emphasised; the global start's best cost per evaluation beside it
//   lasso        leave-one-group-out CV error +- 1 SE against lambda (log-log) per regressed
//                term of a step-regression stage, the chosen lambda marked
//   step samples damping samples sigma_i against x_i and inertia samples m_i against the
//                asymptote's state x_s (mirrored copies as open circles)
#pragma once

#include <map>
#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/run/display_units.h"
#include "engine/report/report_figures.h"
#include "engine/solve/metrics.h"
#include "engine/solve/stage.h"
#include "engine/step_regression/step_regression.h"

namespace vesselid {

// Points per plotted series at most: a minimum and a maximum per pixel column of the trace
// figure's signal (620 pixels wide) and residual (300 pixels) panels, and of cost histories.
constexpr size_t kSignalPoints = 1300;
constexpr size_t kResidualPoints = 650;

// The fits of one record: itself, or its segments in order (fit.trace: t, <output>_measured,
// <output>_simulated), each output shown in units[output] (absent: as computed, no unit).
// False (no figure) when none of them has a measured sample.
bool TraceFigure(const std::string& name, const std::vector<const ExperimentFit*>& fits,
                 const std::vector<std::string>& angle_outputs,
                 const std::map<std::string, DisplayUnit>& units, Figure* figure);

// North against east of one record's fits (outputs `north`, `east`, both in metres). False
// when no segment has both measured.
bool TrackFigure(const std::string& name, const std::vector<const ExperimentFit*>& fits,
                 const std::string& north, const std::string& east, Figure* figure);

// False when there are fewer than two names or no finite correlation.
bool CorrelationFigure(const std::string& name, const std::vector<std::string>& labels,
                       const Eigen::MatrixXd& correlation, Figure* figure);

// False when no history (refinement or global start) has two positive finite costs.
bool CostHistoryFigure(const std::string& name, const StageSummary& summary, Figure* figure);

// False without terms.
bool LassoPathFigure(const std::string& name, const StepRegressionReport& report, Figure* figure);

// states: names of the two regressed states; asymptote_state: index of x_s among them.
// False without samples.
bool StepSamplesFigure(const std::string& name, const StepRegressionReport& report,
                       const std::vector<std::string>& states, int asymptote_state, Figure* figure);

}  // namespace vesselid

#include "engine/report/turning_html.h"

#include <cmath>

#include "engine/output/turning_report.h"
#include "engine/report/report_table_cells.h"

namespace vesselid {

std::string TurningRunsHtml(const std::vector<TurningRun>& runs) {
  if (runs.empty()) return "";
  const std::string unit = runs.front().unit.empty() ? "" : " [" + runs.front().unit + "]";
  std::string rows;
  for (const TurningRun& run : runs) {
    const TurningFigures &m = run.measured, &s = run.simulated;
    auto figure = [](double measured, double simulated) {
      return Num(HtmlNumber(measured, "%.3g")) + Num(HtmlNumber(simulated, "%.3g")) +
             Num(HtmlNumber(TurningErrorPercent(measured, simulated), "%+.1f"));
    };
    rows +=
        "<tr>" + Td(run.stage) + Td(run.experiment) + Td(run.held_out ? "held out" : "training") +
        Num(HtmlNumber(std::abs(run.test.rudder) * 180.0 / M_PI, "%.1f")) +
        Td(run.test.sign > 0 ? "starboard" : "port") + figure(m.advance, s.advance) +
        figure(m.transfer, s.transfer) + figure(m.tactical_diameter, s.tactical_diameter) +
        Num(HtmlNumber(m.time_to_90, "%.1f")) + Num(HtmlNumber(s.time_to_90, "%.1f")) +
        Num(HtmlNumber(m.time_to_180, "%.1f")) + Num(HtmlNumber(s.time_to_180, "%.1f")) + "</tr>\n";
  }
  return "<section id=\"turning\">\n<h2>Turning circles</h2>\n<p>" +
         HtmlEscape(kTurningDefinitions) +
         "</p>\n<div class=\"scroll\"><table class=\"zigzag\">\n<tr>" + Th("stage") +
         Th("experiment") + Th("data") + Th("rudder [deg]") + Th("side") +
         Th("advance measured" + unit) + Th("advance simulated" + unit) + Th("error [%]") +
         Th("transfer measured" + unit) + Th("transfer simulated" + unit) + Th("error [%]") +
         Th("tactical diameter measured" + unit) + Th("tactical diameter simulated" + unit) +
         Th("error [%]") + Th("to 90° measured [s]") + Th("to 90° simulated [s]") +
         Th("to 180° measured [s]") + Th("to 180° simulated [s]") + "</tr>\n" + rows +
         "</table></div>\n</section>\n";
}

}  // namespace vesselid

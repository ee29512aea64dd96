#include "engine/report/zigzag_html.h"

#include <cmath>

#include "engine/output/zigzag_report.h"
#include "engine/report/report_table_cells.h"

namespace vesselid {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

}  // namespace

std::string ZigzagRunsHtml(const std::vector<ZigzagRun>& runs) {
  if (runs.empty()) return "";
  std::string rows;
  for (const ZigzagRun& run : runs) {
    rows += "<tr>" + Td(run.stage) + Td(run.experiment) +
            Td(run.held_out ? "held out" : "training") + Td(ZigzagTestLabel(run)) +
            Num(HtmlNumber(run.measured.first_overshoot * kDegrees, "%.2f")) +
            Num(HtmlNumber(run.simulated.first_overshoot * kDegrees, "%.2f")) +
            Num(HtmlNumber(run.measured.second_overshoot * kDegrees, "%.2f")) +
            Num(HtmlNumber(run.simulated.second_overshoot * kDegrees, "%.2f")) +
            Num(HtmlNumber(run.measured.time_to_first_check, "%.1f")) +
            Num(HtmlNumber(run.simulated.time_to_first_check, "%.1f")) +
            Num(HtmlNumber(run.measured.period, "%.1f")) +
            Num(HtmlNumber(run.simulated.period, "%.1f")) + "</tr>\n";
  }
  const std::string table =
      "<div class=\"scroll\"><table class=\"zigzag\">\n<tr>" + Th("stage") + Th("experiment") +
      Th("data") + Th("δz/ψz [deg]") + Th("1st overshoot measured [deg]") +
      Th("1st overshoot simulated [deg]") + Th("2nd overshoot measured [deg]") +
      Th("2nd overshoot simulated [deg]") + Th("time to 1st check measured [s]") +
      Th("time to 1st check simulated [s]") + Th("period measured [s]") +
      Th("period simulated [s]") + "</tr>\n" + rows + "</table></div>\n";
  return "<section id=\"zigzag\">\n<h2>Zigzag figures</h2>\n<p>" + HtmlEscape(kZigzagDefinitions) +
         "</p>\n" + Fold(table, runs.size(), std::to_string(runs.size()) + " zigzag fits", 24) +
         "</section>\n";
}

}  // namespace vesselid

#include "engine/report/zigzag_html.h"

#include <cmath>
#include <cstdio>

#include "engine/output/held_out_zigzags.h"
#include "engine/output/zigzag_report.h"
#include "engine/report/report_table_cells.h"

namespace vesselid {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

// The held-out runs' overshoots against their 95 % prediction intervals; empty without.
std::string HeldOutZigzagsHtml(const HeldOutZigzagCheck& check) {
  if (check.rows.empty()) return "";
  std::string text = "<h3>Held-out zigzags, measured against predicted</h3>\n<p>";
  for (const HeldOutZigzagCheck::Error& e : check.errors) {
    char line[300];
    std::snprintf(line, sizeof(line),
                  "%s: the 95 %% prediction interval (the run's prediction + m ± t s √(1 + 1/n) "
                  "from its error on %d training zigzags, m = %+.3g°, s = %.3g°) covers %d of %d "
                  "held-out runs. ",
                  e.figure.c_str(), e.runs, e.mean, e.sd, e.covered, e.held_out);
    text += HtmlEscape(line);
  }
  std::string rows;
  for (const HeldOutZigzag& r : check.rows) {
    rows += "<tr>" + Td(r.experiment) + Td(r.test) + Td(r.figure) +
            Num(HtmlNumber(r.measured, "%.2f")) + Num(HtmlNumber(r.predicted, "%.2f")) +
            Num(HtmlNumber(r.low, "%.2f")) + Num(HtmlNumber(r.high, "%.2f")) +
            Td(r.covered ? "yes" : "no") + "</tr>\n";
  }
  return text + "</p>\n<div class=\"scroll\"><table class=\"zigzag\">\n<tr>" + Th("experiment") +
         Th("δz/ψz [deg]") + Th("figure") + Th("measured [deg]") + Th("predicted [deg]") +
         Th("interval from [deg]") + Th("interval to [deg]") + Th("covers") + "</tr>\n" + rows +
         "</table></div>\n";
}

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
         HeldOutZigzagsHtml(CheckHeldOutZigzags(ZigzagEntries(runs))) +
         "</section>\n";
}

}  // namespace vesselid

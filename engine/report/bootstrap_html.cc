#include "engine/report/bootstrap_html.h"

#include "engine/output/bootstrap_report.h"
#include "engine/report/report_table_cells.h"

namespace vesselid {

std::string BootstrapHtml(const StageResult& stage) {
  const BootstrapSummary& b = stage.bootstrap;
  if (!b.done()) {
    return b.message.empty() ? "" : "<p>Bootstrap not run: " + HtmlEscape(b.message) + "</p>\n";
  }
  std::string html = "<h4>Bootstrap</h4>\n<p>" + HtmlEscape(BootstrapDescription(b)) +
                     ": standard error = SD of the replicates, 95 % percentile interval.</p>\n";
  std::string rows;
  for (size_t k = 0; k < b.names.size(); ++k) {
    const bool zero = b.lower[k] <= 0.0 && b.upper[k] >= 0.0;
    rows += "<tr>" + Td(b.names[k]) + Num(HtmlNumber(EstimateValue(stage, b.names[k]))) +
            Num(HtmlNumber(b.std_error[k], "%.3g")) + Num(HtmlNumber(b.lower[k])) +
            Num(HtmlNumber(b.upper[k])) + Td(zero ? "contains 0" : "") + "</tr>\n";
  }
  html += Fold("<table>\n<tr>" + Th("parameter") + Th("estimate") + Th("bootstrap SE") +
                   Th("2.5 %") + Th("97.5 %") + Th("") + "</tr>\n" + rows + "</table>\n",
               b.names.size(), "bootstrap intervals of " + std::to_string(b.names.size()) +
                                   " parameters", 24);
  if (!b.coefficient_names.empty()) {
    rows.clear();
    for (size_t k = 0; k < b.coefficient_names.size(); ++k) {
      rows += "<tr>" + Td(b.coefficient_names[k]) +
              Num(HtmlNumber(100.0 * b.zero_share[k], "%.1f")) +
              Td(UnstableSelection(b.zero_share[k]) ? "unstable" : "") + "</tr>\n";
    }
    html += Fold("<table>\n<tr>" + Th("lasso coefficient") + Th("zero in % of replicates") +
                     Th("") + "</tr>\n" + rows + "</table>\n",
                 b.coefficient_names.size(), "lasso selection stability", 24);
  }
  return html;
}

}  // namespace vesselid

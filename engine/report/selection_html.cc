#include "engine/report/selection_html.h"

#include "engine/output/selection_report.h"
#include "engine/report/report_table_cells.h"

namespace vesselid {

std::string SelectionHtml(const SelectionResult& s) {
  if (s.empty()) return "";
  std::string head = "<tr>" + Th("candidate") + Th("model") + Th("shared parameters") +
                     Th("per-run values") + Th("initial states") + Th("CV fit [%]") + Th("SE [%]");
  for (const std::string& o : s.outputs)
    head += Th(o + " fit [%]") + Th(o + " SD") + Th(o + " RMSE");
  head += Th("AIC") + Th("BIC") + Th("BIC_L") + Th("k-step fit [%] (k samples ahead)") + Th("1-step fit [%]") +
          Th("disturbance") + Th("choice") + "</tr>\n";
  std::string rows;
  for (size_t i = 0; i < s.candidates.size(); ++i) {
    const SelectionCandidate& c = s.candidates[i];
    rows += "<tr>" + Td(c.name) + Td(c.model) + Num(std::to_string(c.shared_parameters)) +
            Num(std::to_string(c.per_run_values)) + Num(std::to_string(c.initial_states)) +
            Num(HtmlNumber(c.score, "%.2f")) + Num(HtmlNumber(c.score_se, "%.2f"));
    for (size_t o = 0; o < s.outputs.size(); ++o) {
      if (o < c.outputs.size()) {
        const SelectionOutputScore& m = c.outputs[o];
        rows += Num(HtmlNumber(m.fit_percent, "%.2f")) + Num(HtmlNumber(m.fit_sd, "%.2f")) +
                Num(HtmlNumber(m.rmse, "%.3g") + (m.unit.empty() ? "" : " " + m.unit));
      } else {
        rows += Td("") + Td("") + Td("");
      }
    }
    const std::string choice = static_cast<int>(i) == s.chosen ? "chosen"
                               : c.within_one_se               ? "within 1 SE"
                               : c.usable                      ? ""
                                                               : "not scored: " + c.message;
    rows +=
        Num(HtmlNumber(c.aic, "%.1f")) + Num(HtmlNumber(c.bic, "%.1f")) +
        Num(HtmlNumber(c.likelihood_bic, "%.1f")) + Num(c.prediction_steps > 0 ? HtmlNumber(c.k_step_fit_percent, "%.2f") + " (k " +
                                            std::to_string(c.prediction_steps) + ")"
                                      : std::string("-")) +
        Num(HtmlNumber(c.one_step_fit_percent, "%.2f")) + Td(c.disturbance) + Td(choice) +
        "</tr>\n";
  }
  return "<section id=\"selection\">\n<h2>Structure selection</h2>\n<p>" +
         HtmlEscape(s.method + " over " + std::to_string(s.folds.size()) +
                    " folds: " + kSelectionDefinitions) +
         "</p>\n<div class=\"scroll\"><table class=\"zigzag\">\n" + head + rows +
         "</table></div>\n<p><strong>Chosen</strong>: " + HtmlEscape(s.reason) +
         "</p>\n</section>\n";
}

}  // namespace vesselid

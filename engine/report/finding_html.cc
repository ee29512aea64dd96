#include "engine/report/finding_html.h"

#include "engine/output/finding_report.h"
#include "engine/report/report_table_cells.h"

namespace vesselid {

std::string FindingsHtml(const std::vector<Finding>& findings) {
  std::string out;
  for (FindingSeverity severity : kSeverityOrder) {
    const int n = CountOf(findings, severity);
    if (n == 0) continue;
    out += "<h4>" + std::string(SeverityHeading(severity)) + " (" + std::to_string(n) +
           ")</h4>\n<ul class=\"findings " + FindingSeverityToString(severity) + "\">\n";
    for (const Finding& f : findings) {
      if (f.severity != severity) continue;
      std::string where;
      if (!f.stage.empty()) where += f.stage == "final" ? "final" : "stage " + f.stage;
      if (!f.experiment.empty()) where += (where.empty() ? "" : ", ") + f.experiment;
      if (!f.parameter.empty()) where += (where.empty() ? "" : ", ") + f.parameter;
      if (!f.output.empty()) where += (where.empty() ? "" : ", ") + f.output;
      if (!f.input.empty()) where += (where.empty() ? "" : ", ") + f.input;
      out += "<li><code>" + std::string(FindingKindToString(f.kind)) + "</code> " +
             (where.empty() ? "" : "<em>" + HtmlEscape(where) + "</em>: ") + HtmlEscape(f.message) +
             (f.count > 1 ? " (x" + std::to_string(f.count) + ")" : "") + "</li>\n";
    }
    out += "</ul>\n";
  }
  return out;
}

}  // namespace vesselid

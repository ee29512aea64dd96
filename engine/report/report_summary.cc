#include "engine/report/report_summary.h"

#include <cmath>

#include "engine/output/finding_report.h"
#include "engine/output/parameter_summary.h"
#include "engine/output/shown_parameters.h"
#include "engine/report/finding_html.h"
#include "engine/report/report_table_cells.h"
#include "engine/report/report_tables.h"

namespace vesselid {

const char kSortScript[] = R"(<script>
document.querySelectorAll('table.sortable').forEach(function (table) {
  table.querySelectorAll('thead th').forEach(function (th, column) {
    th.addEventListener('click', function () {
      var body = table.tBodies[0];
      var rows = Array.prototype.slice.call(body.rows);
      var up = th.dataset.order !== 'up';
      th.dataset.order = up ? 'up' : 'down';
      rows.sort(function (a, b) {
        var x = a.cells[column].textContent, y = b.cells[column].textContent;
        var nx = parseFloat(x), ny = parseFloat(y);
        var c = isNaN(nx) || isNaN(ny) ? x.localeCompare(y) : nx - ny;
        return up ? c : -c;
      });
      rows.forEach(function (row) { body.appendChild(row); });
    });
  });
});
</script>
)";

std::string RunFitTableHtml(const RunFitTable& table) {
  if (table.rows.empty()) return "";
  std::string head = "<thead><tr>" + Th("run") + Th("segments");
  for (size_t o = 0; o < table.outputs.size(); ++o) {
    const std::string unit = table.units[o].empty() ? "" : " [" + table.units[o] + "]";
    head += Th("fit % " + table.outputs[o]) + Th("RMSE " + table.outputs[o] + unit);
  }
  head += Th("√(mean e²)") + "</tr></thead>\n";
  std::string body = "<tbody>\n";
  for (const RunFitRow& row : table.rows) {
    std::string segments = std::to_string(row.segments);
    if (row.diverged > 0) segments += " (" + std::to_string(row.diverged) + " diverged)";
    body += "<tr>" + Td(row.run) + Num(segments);
    for (const ChannelMetrics& m : row.channels) {
      body += Num(HtmlNumber(m.fit_percent, "%.2f")) + Num(HtmlNumber(m.rmse, "%.4g"));
    }
    body += Num(HtmlNumber(row.rms_cost, "%.4g")) + "</tr>\n";
  }
  body += "</tbody>\n";
  std::string foot;
  for (const RunFitSummary& s : table.summary) {
    foot += "<tr class=\"summary\">" +
            Th(s.label + " of " + std::to_string(table.rows.size()) + " runs") + "<td></td>";
    for (size_t o = 0; o < table.outputs.size(); ++o) {
      std::string fit = HtmlNumber(s.fit_percent[o], "%.2f");
      if (!s.run[o].empty()) fit += " (" + s.run[o] + ")";
      foot += Num(fit) + Num(HtmlNumber(s.rmse[o], "%.4g"));
    }
    foot += "<td></td></tr>\n";
  }
  if (!foot.empty()) foot = "<tfoot>\n" + foot + "</tfoot>\n";
  std::string out = "<div class=\"scroll\"><table class=\"sortable runs\">\n" + head + body + foot +
                    "</table></div>\n";
  if (table.worst_first) {
    out += "<p class=\"muted\">" + std::to_string(table.rows.size()) +
           " runs, worst first (lowest fit % of any output); click a heading to sort.</p>\n";
  }
  for (const RunFitRow& row : table.rows) {
    if (row.diverged > 0) {
      out += "<p class=\"warning\">" + HtmlEscape(row.run + ": " + row.diverged_message) + "</p>\n";
    }
  }
  return out;
}

std::string FinalParametersSummaryHtml(const RunConfig& config, const RunResult& result) {
  const std::vector<ParameterReport> reports = ReportParameters(result);
  std::string rows;
  for (size_t i = 0; i < result.parameters.size(); ++i) {
    const DisplayUnit unit = ParameterDisplayUnit(config, result.parameters[i].name);
    const FinalParameter f = Shown(result.parameters[i], unit);
    const ParameterReport r = Shown(reports[i], unit);
    const bool fixed = f.role == ParameterRole::kFixed;
    std::string stages;
    for (const std::string& s : f.stages) stages += (stages.empty() ? "" : ", ") + s;
    std::string interval = fixed ? "—" : "undetermined";
    if (f.runs > 0) {  // per_experiment: its values per run, not one value
      interval = std::to_string(f.runs) + " runs: " + HtmlNumber(f.runs_min, "%.6g") + " to " +
                 HtmlNumber(f.runs_max, "%.6g");
    } else if (std::isfinite(r.interval_low)) {
      interval = "[" + HtmlNumber(r.interval_low, "%.6g") + ", " +
                 HtmlNumber(r.interval_high, "%.6g") + "]";
    }
    const std::string flags = ParameterFlags(r, unit.unit);
    const std::string css = fixed ? " class=\"fixed\"" : !flags.empty() ? " class=\"flagged\"" : "";
    rows += "<tr" + css + ">" + Td(f.name) + Td(unit.unit) +
            Num(f.runs > 0                 ? "per run"
                : f.undetermined && !fixed ? "undetermined"
                                           : HtmlNumber(f.value, "%.8g")) +
            Num(HtmlNumber(f.std_error, "%.4g")) + Num(interval) +
            Num(fixed ? "—" : Bounds(r.lower, r.upper)) + Td(flags) +
            Td(ParameterRoleToString(f.role)) + Td(stages) + Td(f.rule) + "</tr>\n";
  }
  std::string out = "<table class=\"estimates\">\n<tr>" + Th("parameter") + Th("unit") +
                    Th("value") +
                    Th("std. error") + Th("95 % interval (within bounds)") + Th("bounds") +
                    Th("flag") + Th("role") + Th("stages") + Th("rule") + "</tr>\n" + rows +
                    "</table>\n";
  std::string notes;
  for (const ParameterReport& r : reports) {
    if (!r.fusion_note.empty()) notes += "<li>" + HtmlEscape(r.fusion_note) + "</li>\n";
  }
  if (!notes.empty()) out += "<ul class=\"notes\">\n" + notes + "</ul>\n";
  return out;
}

std::string SummarySectionHtml(const RunConfig& config, const RunResult& result) {
  std::string out = "<section id=\"summary\">\n<h2>Summary</h2>\n";
  const std::vector<Finding> all = AllFindings(result);
  out += "<p class=\"verdict " + std::string(VerdictToString(result.verdict)) + "\"><strong>" +
         HtmlEscape(VerdictLine(result.verdict, all)) + "</strong></p>\n";
  out += "<h3 id=\"summary-parameters\">Final parameters</h3>\n<p>" +
         HtmlEscape(DescribeCounts(CountUnknowns(result))) +
         "; shared parameters fused by the <strong>" +
         HtmlEscape(FusionRuleToString(config.fusion)) + "</strong> rule.</p>\n" +
         FinalParametersSummaryHtml(config, result);
  if (const StageResult* last = LastAcceptedStage(result)) {
    out += "<h3 id=\"summary-fit\">Fit per run: stage " + HtmlEscape(last->name) +
           " (identification data)</h3>\n" +
           RunFitTableHtml(PerRunFits(config, last->summary.fits));
  }
  if (!result.final_validation.empty()) {
    out += "<h3 id=\"summary-validation\">Fit per run: final values on held-out data</h3>\n" +
           RunFitTableHtml(PerRunFits(config, result.final_validation));
  }
  out += "<h3 id=\"warnings\">Findings (" + std::to_string(all.size()) + ")</h3>\n";
  out += all.empty() ? std::string("<p>None.</p>\n") : FindingsHtml(all);
  return out + "</section>\n";
}

}  // namespace vesselid

#include "engine/report/held_out_parameters_html.h"

#include "engine/output/held_out_parameters_report.h"
#include "engine/report/report_table_cells.h"

namespace vesselid {

std::string HeldOutParametersHtml(const HeldOutParameters& parameters,
                                  const std::vector<ExperimentFit>& with,
                                  const ParameterUnitOf& unit_of) {
  if (!parameters.active()) return "";
  const std::string names = HeldOutParameterNames(parameters);
  if (!parameters.fitted) {
    return "<p>Per-experiment parameters (" + HtmlEscape(names) +
           ") held at the training runs' mean on the held-out runs (per_experiment: hold).</p>\n";
  }
  const HeldOutParametersTable table = MakeHeldOutParametersTable(parameters, with);
  std::string header = "<tr>" + Th("held-out run");
  std::vector<DisplayUnit> units;  // one per parameter, as for a shared value
  for (const std::string& p : parameters.parameters) {
    units.push_back(unit_of ? unit_of(p) : DisplayUnit{});
    header += Th(WithUnit(p, units.back().unit)) + Th("std. error");
  }
  for (const std::string& output : table.outputs) {
    header += Th(output + " fit % without") + Th(output + " fit % with");
  }
  std::string rows;
  for (const HeldOutRunRow& row : table.rows) {
    rows += "<tr>" + Td(row.experiment);
    for (size_t k = 0; k < parameters.parameters.size(); ++k) {
      const Estimate* found = nullptr;
      for (const Estimate* e : row.estimates) {
        if (e->name.substr(0, e->name.find('[')) == parameters.parameters[k]) found = e;
      }
      const double scale = units[k].scale;
      rows += found == nullptr
                  ? "<td></td><td></td>"
                  : Num(HtmlNumber(scale * found->value, "%.6g")) +
                        Num(found->undetermined ? "undetermined"
                                                : HtmlNumber(scale * found->std_error, "%.2g"));
    }
    for (const std::string& output : table.outputs) {
      const auto at = row.fit.find(output);
      const bool known = at != row.fit.end();
      rows += Num(known ? HtmlNumber(at->second.second, "%.2f") : "") +
              Num(known ? HtmlNumber(at->second.first, "%.2f") : "");
    }
    rows += "</tr>\n";
  }
  rows += "<tr>" + Td("mean");
  for (size_t k = 0; k < parameters.parameters.size(); ++k) rows += "<td></td><td></td>";
  for (const std::string& output : table.outputs) {
    const auto at = table.mean_fit.find(output);
    const bool known = at != table.mean_fit.end();
    rows += Num(known ? HtmlNumber(at->second.second, "%.2f") : "") +
            Num(known ? HtmlNumber(at->second.first, "%.2f") : "");
  }
  rows += "</tr>\n";
  return "<h4>Per-experiment parameters of the held-out runs</h4>\n<p>Each held-out run "
         "estimates its own " +
         HtmlEscape(names) +
         " with the other parameters held; fit % without them (held at the training runs' mean) and "
         "with them.</p>\n" +
         Fold("<table class=\"held-out-parameters\">\n" + header + "</tr>\n" + rows + "</table>\n",
              table.rows.size(), std::to_string(table.rows.size()) + " held-out runs", 24);
}

}  // namespace vesselid

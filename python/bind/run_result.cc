// vesselid.RunResult: a finished run, read-only. Its tables (parameters, fits, stage_table)
// are pandas DataFrames made from the engine's types, in the units results.json gives them
// (fits and traces in the units the data came in); to_json() is results.json's text.
#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>

#include "engine/diagnose/run_findings.h"
#include "engine/output/parameter_summary.h"
#include "engine/output/run_traces.h"
#include "engine/output/selection_report.h"
#include "engine/report/report_tables.h"
#include "engine/run/display_units.h"
#include "python/bind/frames.h"
#include "python/bind/types.h"

namespace vesselid::python {
namespace {

// The run's findings, then each stage's, in order (results.json's order).
std::vector<Finding> Findings(const Run& run) {
  std::vector<Finding> all = run.result.findings;
  for (const StageResult& stage : run.result.stages) {
    all.insert(all.end(), stage.findings.begin(), stage.findings.end());
  }
  return all;
}

py::object Parameters(const Run& run) {
  const RunConfig& config = *run.config;
  const std::vector<ParameterReport> reports = ReportParameters(run.result);
  const std::vector<std::string> order = {
      "name", "value", "std_error", "lower", "upper", "interval_low", "interval_high", "role",
      "unit", "undetermined", "at_bound", "shown_unit", "shown_scale", "stages"};
  std::map<std::string, py::list> column;
  for (size_t i = 0; i < run.result.parameters.size(); ++i) {
    const FinalParameter& f = run.result.parameters[i];
    const ParameterReport& r = reports[i];
    const std::string unit = ParameterModelUnit(config.model->info(), f.name);
    const DisplayUnit shown = ParameterDisplayUnit(config, f.name);
    std::string stages;
    for (const std::string& s : f.stages) stages += (stages.empty() ? "" : ", ") + s;
    column["name"].append(f.name);
    column["value"].append(f.value);
    column["std_error"].append(f.std_error);
    column["lower"].append(r.lower);
    column["upper"].append(r.upper);
    column["interval_low"].append(r.interval_low);
    column["interval_high"].append(r.interval_high);
    column["role"].append(ParameterRoleToString(f.role));
    column["unit"].append(unit);
    column["undetermined"].append(f.undetermined);
    column["at_bound"].append(r.bound < 0 ? "lower" : r.bound > 0 ? "upper" : "");
    column["shown_unit"].append(unit.empty() ? "" : shown.unit);
    column["shown_scale"].append(unit.empty() ? 1.0 : shown.scale);
    column["stages"].append(stages);
  }
  py::dict columns;
  for (const std::string& name : order) columns[py::str(name)] = column[name];
  return Frame(columns, order, "name");
}

// The fit metrics per stage, experiment and output, in the units the data came in: "fit" on
// the training runs, "validation" on held-out runs, "final_validation".
py::object Fits(const Run& run) {
  const std::vector<std::string> order = {"stage", "role", "experiment", "output", "unit",
                                          "samples", "rmse", "mae", "r2", "fit_percent",
                                          "hold_mae", "noise"};
  std::map<std::string, py::list> column;
  auto add = [&](const std::string& stage, const char* role,
                 const std::vector<ExperimentFit>& fits) {
    for (const ExperimentFit& fit : fits) {
      for (const ChannelMetrics& m : fit.channels) {
        const DisplayUnit unit = OutputDisplayUnit(*run.config, m.experiment, m.output);
        column["stage"].append(stage);
        column["role"].append(role);
        column["experiment"].append(m.experiment);
        column["output"].append(m.output);
        column["unit"].append(unit.unit);
        column["samples"].append(m.samples);
        column["rmse"].append(unit.scale * m.rmse);
        column["mae"].append(unit.scale * m.mae);
        column["r2"].append(m.r2);
        column["fit_percent"].append(m.fit_percent);
        column["hold_mae"].append(unit.scale * m.hold_mae);
        column["noise"].append(unit.scale * m.noise);
      }
    }
  };
  for (const StageResult& s : run.result.stages) {
    add(s.name, "fit", s.summary.fits);
    add(s.name, "validation", s.validation);
  }
  add("", "final_validation", run.result.final_validation);
  py::dict columns;
  for (const std::string& name : order) columns[py::str(name)] = column[name];
  return Frame(columns, order);
}

py::object StageTable(const Run& run) {
  const std::vector<std::string> order = {"stage", "verdict", "cost", "comparable_cost",
                                          "iterations"};
  std::map<std::string, py::list> column;
  for (const StageResult& s : run.result.stages) {
    column["stage"].append(s.name);
    column["verdict"].append(VerdictToString(s.verdict));
    column["cost"].append(s.summary.local().final_cost);
    column["comparable_cost"].append(s.comparable_cost);
    column["iterations"].append(s.summary.local().iterations);
  }
  py::dict columns;
  for (const std::string& name : order) columns[py::str(name)] = column[name];
  return Frame(columns, order, "stage");
}

py::dict Traces(const Run& run) {
  py::dict traces;
  for (const NamedTrace& trace : RunTraces(*run.config, run.result)) {
    traces[py::str(trace.name)] = FrameOf(trace.trace);
  }
  return traces;
}

std::string Number(double value) {
  if (std::isnan(value)) return "";
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

// The verdict, the parameters in the units the data came in, and the warnings: a notebook's
// view of the run.
std::string Html(const Run& run) {
  const RunResult& result = run.result;
  const char* verdict = VerdictToString(result.verdict);
  const char* colour = result.verdict == Verdict::kGood       ? "#1a7f37"
                       : result.verdict == Verdict::kDoubtful ? "#9a6700"
                                                              : "#cf222e";
  std::string html = std::string("<p><b>vesselid run</b>: verdict <b style='color:") + colour +
                     "'>" + verdict + "</b></p>\n<table><tr><th>name</th><th>value</th>"
                     "<th>std_error</th><th>interval_low</th><th>interval_high</th><th>unit</th>"
                     "<th>role</th><th>at_bound</th></tr>\n";
  const std::vector<ParameterReport> reports = ReportParameters(result);
  for (size_t i = 0; i < result.parameters.size(); ++i) {
    const FinalParameter& f = result.parameters[i];
    const ParameterReport& r = reports[i];
    const DisplayUnit shown = ParameterDisplayUnit(*run.config, f.name);
    html += "<tr><td>" + HtmlEscape(f.name) + "</td><td>" + Number(shown.scale * f.value) +
            "</td><td>" + Number(shown.scale * f.std_error) + "</td><td>" +
            Number(shown.scale * r.interval_low) + "</td><td>" +
            Number(shown.scale * r.interval_high) + "</td><td>" + HtmlEscape(shown.unit) +
            "</td><td>" + ParameterRoleToString(f.role) + "</td><td>" +
            (r.bound < 0 ? "lower" : r.bound > 0 ? "upper" : "") + "</td></tr>\n";
  }
  html += "</table>\n";
  std::string items;
  int shown = 0;
  for (const Finding& f : Findings(run)) {
    if (f.severity == FindingSeverity::kInfo || ++shown > 20) continue;
    items += "<li>" + std::string(FindingSeverityToString(f.severity)) + ": " +
             HtmlEscape(f.message) + "</li>";
  }
  return html + (items.empty() ? "<p>no warnings</p>" : "<ul>" + items + "</ul>");
}

// The findings of one kind and/or severity; a kind or severity that does not exist is an
// error, not an empty list (`vesselid findings` lists the kinds).
std::vector<Finding> Find(const Run& run, const py::object& kind, const py::object& severity) {
  std::string wanted_kind, wanted_severity;
  if (!kind.is_none()) {
    wanted_kind = py::str(kind);
    FindingKind known;
    if (!StringToFindingKind(wanted_kind, &known)) {
      throw py::value_error("no finding kind '" + wanted_kind + "' (`vesselid findings` lists them)");
    }
  }
  if (!severity.is_none()) {
    wanted_severity = py::str(severity);
    FindingSeverity known;
    if (!StringToFindingSeverity(wanted_severity, &known)) {
      throw py::value_error("no severity '" + wanted_severity + "' (info, warning, failure)");
    }
  }
  std::vector<Finding> found;
  for (const Finding& f : Findings(run)) {
    if (!wanted_kind.empty() && wanted_kind != FindingKindToString(f.kind)) continue;
    if (!wanted_severity.empty() && wanted_severity != FindingSeverityToString(f.severity)) continue;
    found.push_back(f);
  }
  return found;
}

}  // namespace

void BindRunResult(py::module_& m) {
  py::class_<Run, std::shared_ptr<Run>>(
      m, "RunResult",
      "What `vesselid run` writes, from Python.\n\n"
      "verdict      'good', 'doubtful' or 'failed'\n"
      "findings     list of Finding (the run's and every stage's); find(kind=, severity=)\n"
      "stages       list of StageResult; stage_table: one row per stage (verdict, cost, "
      "comparable_cost, iterations)\n"
      "parameters   DataFrame by parameter name: value, std_error, lower, upper, interval_low, "
      "interval_high, role, unit, undetermined, at_bound, shown_unit, shown_scale, stages (SI "
      "units; shown = shown_scale x value in the unit the data came in)\n"
      "fits         DataFrame of the fit metrics per stage, experiment and output (role fit, "
      "validation, final_validation), in the units the data came in\n"
      "traces       {'<stage>.<experiment>': DataFrame}: the CLI's traces/ files\n"
      "model        the IdentifiedModel (simulate() flies it as the run did)\n"
      "selection    the structure selection that chose the config (vesselid.select), or None\n"
      "summary      report.txt's text; to_json(): results.json's text; json: it as a dict")
      .def_property_readonly("verdict", [](const Run& r) { return VerdictToString(r.result.verdict); })
      .def_property_readonly("findings", &Findings)
      .def("find", &Find,
           py::arg("kind") = py::none(), py::arg("severity") = py::none(),
           "The findings of one kind and/or severity.")
      .def_property_readonly(
          "stages",
          [](py::object self) {
            py::list stages;
            const Run& r = self.cast<const Run&>();
            for (const StageResult& s : r.result.stages) {
              stages.append(py::cast(&s, py::return_value_policy::reference_internal, self));
            }
            return stages;
          })
      .def_property_readonly("stage_table", &StageTable)
      .def_property_readonly("parameters", &Parameters)
      .def_property_readonly("fits", &Fits)
      .def_property_readonly("traces", &Traces)
      .def_readonly("model", &Run::model)
      .def_property_readonly("selection",
                             [](const Run& r) -> py::object {
                               if (!r.result.selection) return py::none();
                               return py::module_::import("json").attr("loads")(
                                   SelectionToJson(*r.result.selection).dump());
                             })
      .def_readonly("summary", &Run::summary)
      .def_property_readonly("json",
                             [](const Run& r) { return py::module_::import("json").attr("loads")(r.json); })
      .def("to_json", [](const Run& r) { return r.json; },
           "results.json's text (the bytes `vesselid run` writes, before indentation).")
      .def("_repr_html_", &Html)
      .def("__repr__", [](const Run& r) {
        return "<vesselid.RunResult verdict=" + std::string(VerdictToString(r.result.verdict)) +
               ", " + std::to_string(r.result.parameters.size()) + " parameters, " +
               std::to_string(Findings(r).size()) + " findings>";
      });
}

}  // namespace vesselid::python

#include "engine/design/design_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "engine/base/atomic_file.h"
#include "engine/base/json_number.h"
#include "engine/design/design_names.h"
#include "engine/output/output_folder.h"
#include "engine/output/published_set.h"
#include "engine/report/report_figures.h"
#include "engine/report/report_plots.h"
#include "engine/report/report_table_cells.h"
#include "engine/report/report_tables.h"

namespace vesselid {
namespace {

using json = nlohmann::json;

std::vector<const PlanSummary*> Plans(const DesignResult& r) {
  std::vector<const PlanSummary*> plans = {&r.planned};
  for (const PlanSummary& a : r.alternatives) plans.push_back(&a);
  return plans;
}

json ByParameter(const DesignResult& r, const std::vector<double>& values) {
  json j = json::object();
  for (size_t i = 0; i < r.parameters.size() && i < values.size(); ++i) {
    j[r.parameters[i]] = JsonNumber(values[i]);  // null: undetermined
  }
  return j;
}

std::string Number(double value, const char* format = "%.4g") {
  if (std::isinf(value)) return "undetermined";
  if (!std::isfinite(value)) return "-";
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

// An input column's factor from model units (degrees where the config gives them).
double InputScale(const DesignResult& r, size_t i) {
  return r.input_degrees[i] ? (1.0 / kDesignDegree) : 1.0;
}

std::string InputHeader(const DesignResult& r, size_t i) {
  return r.input_degrees[i] ? r.inputs[i] + "_deg" : r.inputs[i];
}

// How many times the widest interval shrinks: a number, "determined" (undetermined today,
// finite after) or "undetermined" (both).
std::string ShrinkText(double shrink) {
  if (std::isinf(shrink)) return "determined";
  if (!std::isfinite(shrink)) return "undetermined";
  return Number(shrink, "%.3g") + "x";
}

json ShrinkJson(double shrink) {
  if (std::isfinite(shrink)) return shrink;
  return ShrinkText(shrink);
}

}  // namespace

json DesignToJson(const DesignResult& r) {
  json alternatives = json::object(), spread = json::object(), plans = json::array();
  json shrink = json::object();
  for (const PlanSummary* p : Plans(r)) {
    if (p->ok && p != &r.planned) alternatives[p->name] = ByParameter(r, p->std_errors);
    if (!p->std_error_low.empty()) {
      json s = json::object();
      for (size_t i = 0; i < r.parameters.size(); ++i) {
        s[r.parameters[i]] = {JsonNumber(p->std_error_low[i]), JsonNumber(p->std_error_median[i]),
                              JsonNumber(p->std_error_high[i])};
      }
      spread[p->name] = s;
    }
    if (p->ok) shrink[p->name] = ShrinkJson(p->shrink);
    json item = {{"name", p->name},
                 {"ok", p->ok},
                 {"duration", p->duration},
                 {"criterion", JsonNumber(p->criterion)},
                 {"box_violation", JsonNumber(p->box_violation)}};
    if (!p->ok) item["error"] = p->error;
    plans.push_back(item);
  }
  json parameters = json::array();
  for (size_t i = 0; i < r.parameters.size(); ++i) {
    parameters.push_back({{"name", r.parameters[i]},
                          {"unit", r.parameter_units[i]},
                          {"value", r.values[i]},
                          {"std_error", JsonNumber(r.current_std_errors[i])}});
  }
  json noise = json::object();
  for (size_t o = 0; o < r.outputs.size(); ++o) {
    if (std::isfinite(r.noise[o])) noise[r.outputs[o]] = r.noise[o];
  }
  json j = {
      {"run", r.run},
      {"model", r.model},
      {"family", r.family},
      {"criterion", r.criterion},
      {"duration", r.duration},
      {"sample_time", r.sample_time},
      {"parameters", parameters},
      {"noise", noise},
      {"predicted_std_errors",
       {{"current", ByParameter(r, r.current_std_errors)},
        {"planned", ByParameter(r, r.planned.std_errors)},
        {"alternatives", alternatives}}},
      {"widest", {{"parameter", r.widest >= 0 ? r.parameters[r.widest] : ""}, {"shrink", shrink}}},
      {"plans", plans},
      {"limits", {{"respected", r.limit_violations.empty()}, {"violations", r.limit_violations}}},
      {"search",
       {{"algorithm", r.algorithm},
        {"evaluations", r.evaluations},
        {"design_variables", r.design_variables},
        {"ensemble_members", r.members}}},
      {"notes", r.notes},
      {"files", {"planned_input.csv", "predicted.csv", "design.txt", "report.html"}}};
  if (!spread.empty()) j["predicted_std_error_spread"] = spread;
  return j;
}

std::string DesignText(const DesignResult& r) {
  std::ostringstream out;
  out << "Next experiment for " << r.model << " (run " << r.run << ")\n";
  out << "criterion " << r.criterion << ", " << Number(r.duration, "%.1f") << " s at "
      << Number(r.sample_time, "%.3g") << " s sampling";
  if (r.members > 0) out << ", averaged over " << r.members << " ensemble members";
  out << "\n\nPredicted standard errors after adding each experiment\n";
  std::vector<const PlanSummary*> plans = Plans(r);
  char cell[64];
  std::snprintf(cell, sizeof(cell), "%-12s %12s %12s", "parameter", "value", "today");
  out << cell;
  for (const PlanSummary* p : plans) {
    std::snprintf(cell, sizeof(cell), " %13s", p->name.c_str());
    out << cell;
  }
  out << "\n";
  for (size_t i = 0; i < r.parameters.size(); ++i) {
    std::snprintf(cell, sizeof(cell), "%-12s %12s %12s", r.parameters[i].c_str(),
                  Number(r.values[i]).c_str(), Number(r.current_std_errors[i]).c_str());
    out << cell;
    for (const PlanSummary* p : plans) {
      std::snprintf(cell, sizeof(cell), " %13s",
                    p->ok ? Number(p->std_errors[i]).c_str() : "failed");
      out << cell;
    }
    out << "\n";
  }
  if (r.widest >= 0) {
    out << "\nThe widest interval today, " << r.parameters[r.widest] << ", shrinks by:";
    for (const PlanSummary* p : plans) {
      if (p->ok) out << "  " << p->name << " " << ShrinkText(p->shrink);
    }
    out << "\n";
  }
  for (const PlanSummary* p : plans) {
    if (p->ok && p->box_violation > 0.0) {
      out << p->name << ": leaves the box by " << Number(p->box_violation) << "\n";
    }
    if (!p->ok) out << p->name << ": " << p->error << "\n";
  }
  out << (r.limit_violations.empty() ? "\nThe plan keeps every limit (amplitude, rate, duration"
                                     : "\nLIMITS NOT KEPT:\n");
  if (r.limit_violations.empty()) out << (r.options.box.empty() ? ").\n" : ", box).\n");
  for (const std::string& v : r.limit_violations) out << "  " << v << "\n";
  for (const std::string& note : r.notes) out << "note: " << note << "\n";
  return out.str();
}

namespace {

// The plan as CSV: t, the inputs (in the config's units), and the predicted outputs when
// `outputs`.
std::string PlanCsv(const DesignResult& r, bool outputs) {
  std::ostringstream out;
  out << "t";
  for (size_t i = 0; i < r.inputs.size(); ++i) out << "," << InputHeader(r, i);
  if (outputs) {
    for (const std::string& o : r.outputs) out << "," << o;
  }
  out << "\n";
  const PlannedRecord& record = r.planned.record;
  char number[40];
  for (size_t k = 0; k < record.time.size(); ++k) {
    std::snprintf(number, sizeof(number), "%.6f", record.time[k]);
    out << number;
    for (size_t i = 0; i < r.inputs.size(); ++i) {
      std::snprintf(number, sizeof(number), ",%.9g", record.inputs(k, i) * InputScale(r, i));
      out << number;
    }
    for (size_t o = 0; outputs && o < r.outputs.size(); ++o) {
      std::snprintf(number, sizeof(number), ",%.9g", record.outputs(k, o));
      out << number;
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace

std::string PlannedInputCsv(const DesignResult& r) { return PlanCsv(r, false); }

std::string PredictedCsv(const DesignResult& r) { return PlanCsv(r, true); }

namespace {

// Relative standard errors (se / |value|, log scale) per parameter for today and each plan.
Figure StdErrorFigure(const DesignResult& r) {
  Figure f;
  f.name = "design_std_errors";
  f.height = 380;
  std::vector<const PlanSummary*> plans = Plans(r);
  std::ostringstream data;
  for (size_t i = 0; i < r.parameters.size(); ++i) {
    const double value = std::abs(r.values[i]) > 0.0 ? std::abs(r.values[i]) : 1.0;
    data << '"' << r.parameters[i] << "\" "
         << GnuplotNumber(std::isfinite(r.current_std_errors[i]) ? r.current_std_errors[i] / value
                                                                 : NAN);
    for (const PlanSummary* p : plans) {
      data << " " << GnuplotNumber(p->ok ? p->std_errors[i] / value : NAN);
    }
    data << "\n";
  }
  f.data.push_back(data.str());
  std::string script = std::string(kPlotStyle) +
                       "set style data histogram\nset style histogram cluster gap 1\n"
                       "set style fill solid 0.8 border -1\nset logscale y\n"
                       "set ylabel 'standard error / |value|'\nset key outside right\n"
                       "plot D0 using 2:xtic(1) title 'today'";
  for (size_t k = 0; k < plans.size(); ++k) {
    script += ", '' using " + std::to_string(k + 3) + " title " + GnuplotString(plans[k]->name);
  }
  f.script = script + "\n";
  return f;
}

// The planned inputs and the predicted outputs against time, a panel each.
Figure PlanFigure(const DesignResult& r) {
  Figure f;
  f.name = "design_plan";
  const PlannedRecord& record = r.planned.record;
  const int panels = static_cast<int>(r.inputs.size() + r.outputs.size());
  f.height = 120 * panels + 60;
  std::string script = std::string(kPlotStyle) + "set multiplot layout " + std::to_string(panels) +
                       ",1\nset key off\n";
  auto series = [&](const Eigen::MatrixXd& m, int column, double scale) {
    SeriesPiece piece;
    for (size_t k = 0; k < record.time.size(); ++k) {
      if (!std::isfinite(m(k, column))) continue;
      piece.x.push_back(record.time[k]);
      piece.y.push_back(m(k, column) * scale);
    }
    return SeriesData({piece}, kSignalPoints);
  };
  int d = 0;
  for (size_t i = 0; i < r.inputs.size(); ++i, ++d) {
    f.data.push_back(series(record.inputs, static_cast<int>(i), InputScale(r, i)));
    script += "set ylabel " + GnuplotString(InputHeader(r, i) + " (plan)") + "\nplot D" +
              std::to_string(d) + " with lines lw 2 lc rgb '#34506b'\n";
  }
  for (size_t o = 0; o < r.outputs.size(); ++o, ++d) {
    f.data.push_back(series(record.outputs, static_cast<int>(o), 1.0));
    script += std::string(o + 1 == r.outputs.size() ? "set xlabel 't [s]'\n" : "") + "set ylabel " +
              GnuplotString(r.outputs[o] + " (predicted)") + "\nplot D" + std::to_string(d) +
              " with lines lw 1.5 lc rgb '#b5532a'\n";
  }
  f.script = script + "unset multiplot\n";
  return f;
}

// North against east with the box, for models with positions n and e.
bool PlanTrackFigure(const DesignResult& r, Figure* f) {
  int north = -1, east = -1;
  for (size_t o = 0; o < r.outputs.size(); ++o) {
    if (r.outputs[o] == "n") north = static_cast<int>(o);
    if (r.outputs[o] == "e") east = static_cast<int>(o);
  }
  if (north < 0 || east < 0) return false;
  const PlannedRecord& record = r.planned.record;
  f->name = "design_track";
  f->height = 500;
  f->width = 600;
  SeriesPiece piece;
  for (size_t k = 0; k < record.time.size(); ++k) {
    piece.x.push_back(record.outputs(k, east));
    piece.y.push_back(record.outputs(k, north));
  }
  f->data.push_back(SeriesData({piece}, kSignalPoints));
  std::string script = std::string(kPlotStyle) +
                       "set size ratio -1\nset xlabel 'e [m]'\nset ylabel 'n [m]'\nset key off\n";
  const auto n_box = r.options.box.find("n"), e_box = r.options.box.find("e");
  if (n_box != r.options.box.end() && e_box != r.options.box.end() && !record.time.empty()) {
    const double n0 = record.outputs(0, north), e0 = record.outputs(0, east);
    script += "set object 1 rect from " + GnuplotNumber(e0 + e_box->second.first) + "," +
              GnuplotNumber(n0 + n_box->second.first) + " to " +
              GnuplotNumber(e0 + e_box->second.second) + "," +
              GnuplotNumber(n0 + n_box->second.second) +
              " fillstyle empty border lc rgb '#8a1c1c' lw 2\n";
  }
  f->script = script + "plot D0 with lines lw 2 lc rgb '#34506b'\n";
  return true;
}

}  // namespace

std::string DesignHtml(const DesignResult& r) {
  std::vector<Figure> figures = {StdErrorFigure(r), PlanFigure(r)};
  Figure track;
  if (PlanTrackFigure(r, &track)) figures.push_back(track);
  const FigureRendering drawn = RenderFigures(figures);
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>"
       << HtmlEscape("vesselid design: " + r.model) << "</title>\n<style>\n"
       << "body { font-family: \"DejaVu Sans\", Verdana, sans-serif; font-size: 14px; "
          "max-width: 1180px; margin: 0 auto; padding: 0 24px 60px; color: #222; }\n"
       << "table { border-collapse: collapse; margin: 6px 0 14px; font-size: 13px; }\n"
       << "th, td { border: 1px solid #d3d8de; padding: 3px 8px; text-align: left; }\n"
       << "th { background: #edf1f5; } td.num { text-align: right; white-space: nowrap; }\n"
       << ".warning { color: #8a1c1c; }\n</style>\n</head>\n<body>\n";
  html << "<h1>Next experiment for " << HtmlEscape(r.model) << "</h1>\n<p>From the run "
       << HtmlEscape(r.run) << "; criterion " << HtmlEscape(r.criterion) << ", "
       << Number(r.duration, "%.1f") << " s sampled every " << Number(r.sample_time, "%.3g") << " s"
       << (r.members > 0 ? ", averaged over " + std::to_string(r.members) + " ensemble members"
                         : "")
       << ". The plan is <code>planned_input.csv</code>.</p>\n";
  html << "<h2>Predicted standard errors</h2>\n<table>\n<tr>" << Th("parameter") << Th("unit")
       << Th("value") << Th("today");
  const std::vector<const PlanSummary*> plans = Plans(r);
  for (const PlanSummary* p : plans) html << Th(p->name);
  html << "</tr>\n";
  for (size_t i = 0; i < r.parameters.size(); ++i) {
    html << "<tr>" << Td(r.parameters[i]) << Td(r.parameter_units[i]) << Num(Number(r.values[i]))
         << Num(Number(r.current_std_errors[i]));
    for (const PlanSummary* p : plans) {
      std::string cell = p->ok ? Number(p->std_errors[i]) : "failed";
      if (p->ok && !p->std_error_low.empty()) {
        cell += " [" + Number(p->std_error_low[i]) + ", " + Number(p->std_error_median[i]) + ", " +
                Number(p->std_error_high[i]) + "]";
      }
      html << Num(cell);
    }
    html << "</tr>\n";
  }
  if (r.widest >= 0) {
    html << "<tr><th colspan=\"4\">" << HtmlEscape(r.parameters[r.widest])
         << " (widest today) shrinks</th>";
    for (const PlanSummary* p : plans) html << Num(p->ok ? ShrinkText(p->shrink) : "-");
    html << "</tr>\n";
  }
  html << "</table>\n";
  if (r.members > 0) {
    html << "<p>In brackets: the 5th, 50th and 95th percentiles over the ensemble members (what "
            "to expect should the estimate be wrong).</p>\n";
  }
  auto figure = [&](size_t k) {
    if (k < drawn.svg.size() && !drawn.svg[k].empty()) html << drawn.svg[k] << "\n";
  };
  figure(0);
  html << "<h2>The plan</h2>\n";
  figure(1);
  if (figures.size() > 2) {
    html << "<h3>Predicted track</h3>\n";
    figure(2);
  }
  html << "<h2>Plans compared</h2>\n<table>\n<tr>" << Th("plan") << Th("duration [s]")
       << Th("criterion") << Th("outside the box") << "</tr>\n";
  for (const PlanSummary* p : plans) {
    html << "<tr>" << Td(p->name) << Num(p->ok ? Number(p->duration, "%.1f") : "-")
         << Num(p->ok ? Number(p->criterion) : HtmlEscape(p->error))
         << Num(p->ok ? Number(p->box_violation) : "-") << "</tr>\n";
  }
  html << "</table>\n<h2>Limits</h2>\n";
  if (r.limit_violations.empty()) {
    html << "<p>The plan keeps every input within its range and rate"
         << (r.options.box.empty() ? "" : ", and its predicted track within the box") << ".</p>\n";
  } else {
    html << "<ul class=\"warning\">\n";
    for (const std::string& v : r.limit_violations) html << "<li>" << HtmlEscape(v) << "</li>\n";
    html << "</ul>\n";
  }
  for (const std::string& note : r.notes) html << "<p>" << HtmlEscape(note) << "</p>\n";
  if (!drawn.error.empty()) html << "<p class=\"warning\">" << HtmlEscape(drawn.error) << "</p>\n";
  html << "</body>\n</html>\n";
  return html.str();
}

bool WriteDesign(const DesignResult& r, std::string out_dir, std::string* error) {
  if (out_dir.empty() && !DefaultOutFolder(r.run, "design", &out_dir, error)) return false;
  std::error_code same_error;
  if (std::filesystem::equivalent(out_dir, r.run, same_error)) {
    *error = "--out " + out_dir + ": the run's own folder (its report.html would be replaced); "
             "leave --out out for <run>/design";
    return false;
  }
  const std::string json_text = DesignToJson(r).dump(2) + "\n";
  const std::string text = DesignText(r), csv = PlannedInputCsv(r), predicted = PredictedCsv(r);
  const std::string html = DesignHtml(r);
  auto writer = [](const std::string& content) {
    return [content](const std::string& path, std::string* message) {
      return WriteFileAtomically(path, content, message);
    };
  };
  return PublishSet(out_dir, "design", (std::filesystem::path(r.run) / "results.json").string(),
                    {{"planned_input.csv", writer(csv)},
                     {"predicted.csv", writer(predicted)},
                     {"design.txt", writer(text)},
                     {"report.html", writer(html)},
                     {"design.json", writer(json_text)}},
                    error);
}

}  // namespace vesselid

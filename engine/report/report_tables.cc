#include "engine/report/report_tables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "engine/run/display_units.h"
#include "engine/output/parameter_summary.h"
#include "engine/report/report_table_cells.h"
#include "engine/output/shown_parameters.h"

namespace vesselid {
namespace {

constexpr size_t kOpenRows = 24;  // longer tables are folded (<details>)

// value ± 1.96 SE within [lower, upper], or "undetermined".
std::string Interval(double value, double std_error, bool undetermined, double lower = -INFINITY,
                     double upper = INFINITY) {
  if (undetermined || !std::isfinite(std_error)) return "undetermined";
  return "[" + HtmlNumber(std::max(lower, value - 1.96 * std_error), "%.6g") + ", " +
         HtmlNumber(std::min(upper, value + 1.96 * std_error), "%.6g") + "]";
}

// An estimate on its bound, its interval clipped to the bounds (parameter_summary.h).
std::string EstimateRow(const Estimate& e, bool with_experiment, const std::string& unit) {
  const int bound = BoundSide(e.value, e.lower, e.upper);
  const bool clipped =
      std::isfinite(e.std_error) && !e.undetermined &&
      (e.value - 1.96 * e.std_error < e.lower || e.value + 1.96 * e.std_error > e.upper);
  std::string flag = bound == 0 ? "" : bound < 0 ? "on its lower bound" : "on its upper bound";
  if (clipped) flag += (flag.empty() ? "" : "; ") + std::string("interval clipped");
  std::string row = std::string(flag.empty() ? "<tr>" : "<tr class=\"flagged\">") + Td(e.name);
  if (with_experiment) {
    row += Td(e.experiment) + Td(e.kind == EstimateKind::kInitialState ? "initial state"
                                        : e.kind == EstimateKind::kNoise ? "noise"
                                                                         : "parameter");
  }
  return row + Td(ParameterRoleToString(e.role)) + Td(unit) + Num(HtmlNumber(e.value, "%.8g")) +
         Num(HtmlNumber(e.std_error, "%.4g")) +
         Num(Interval(e.value, e.std_error, e.undetermined, e.lower, e.upper)) +
         Num(HtmlNumber(e.start, "%.6g")) + Num(Bounds(e.lower, e.upper)) + Td(flag) + "</tr>\n";
}

}  // namespace

std::string HtmlEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string HtmlNumber(double value, const char* format) {
  if (!std::isfinite(value)) return "—";
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::vector<std::vector<const ExperimentFit*>> GroupByRecord(
    const std::vector<ExperimentFit>& fits) {
  std::vector<std::vector<const ExperimentFit*>> groups;
  std::map<std::string, size_t> index;
  for (const ExperimentFit& fit : fits) {
    const auto [at, added] = index.emplace(RecordName(fit.experiment), groups.size());
    if (added) groups.emplace_back();
    groups[at->second].push_back(&fit);
  }
  return groups;
}

std::string MetricsTable(const std::vector<const ExperimentFit*>& fits, const RunConfig* config) {
  std::string rows;
  size_t count = 0;
  for (const ExperimentFit* fit : fits) {
    for (const ChannelMetrics& m : fit->channels) {
      const DisplayUnit unit =
          config ? OutputDisplayUnit(*config, m.experiment, m.output) : DisplayUnit{};
      rows += "<tr>" + Td(m.experiment) + Td(m.output) + (config ? Td(unit.unit) : "") +
              Num(std::to_string(m.samples)) + Num(HtmlNumber(unit.scale * m.rmse, "%.4g")) +
              Num(HtmlNumber(unit.scale * m.mae, "%.4g")) + Num(HtmlNumber(m.r2, "%.5f")) +
              Num(HtmlNumber(m.fit_percent, "%.2f")) + Num(HtmlNumber(fit->rms_cost, "%.4g")) +
              "</tr>\n";
      ++count;
    }
  }
  if (count == 0) return "";
  const std::string table = "<table class=\"metrics\">\n<tr>" + Th("experiment") + Th("output") +
                            (config ? Th("unit") : "") + Th("samples") + Th("RMSE") + Th("MAE") +
                            Th("R²") + Th("fit %") + Th("√(mean e²)") + "</tr>\n" + rows +
                            "</table>\n";
  return Fold(table, count, "metrics of " + std::to_string(count) + " channels", kOpenRows);
}

std::string EstimatesTables(const std::vector<Estimate>& estimates, const RunConfig* config) {
  const std::string header = Th("role") + Th("unit") + Th("value") + Th("std. error") + Th("95 % interval") +
                             Th("start") + Th("bounds") + Th("flag") + "</tr>\n";
  std::string shared, per_experiment, fixed;
  size_t shared_count = 0, per_experiment_count = 0, fixed_count = 0;
  for (const Estimate& estimate : estimates) {
    const DisplayUnit unit =
        config ? ParameterDisplayUnit(*config, estimate.name) : DisplayUnit{};
    const Estimate e = Shown(estimate, unit);
    if (e.role == ParameterRole::kFixed) {
      fixed += "<tr>" + Td(e.name) + Td(e.experiment) + Td(unit.unit) +
               Num(HtmlNumber(e.value, "%.8g")) + "</tr>\n";
      ++fixed_count;
    } else if (!e.experiment.empty()) {
      per_experiment += EstimateRow(e, true, unit.unit);
      ++per_experiment_count;
    } else {
      shared += EstimateRow(e, false, unit.unit);
      ++shared_count;
    }
  }
  std::string out;
  if (shared_count > 0) {
    out += "<table class=\"estimates\">\n<tr>" + Th("parameter") + header + shared + "</table>\n";
  } else {
    out += "<p>No parameter was estimated by this stage alone.</p>\n";
  }
  if (per_experiment_count > 0) {
    out += Fold("<table class=\"estimates\">\n<tr>" + Th("name") + Th("experiment") + Th("kind") +
                    header + per_experiment + "</table>\n",
                per_experiment_count,
                std::to_string(per_experiment_count) +
                    " per-experiment estimates (parameters and initial states)",
                12);
  }
  if (fixed_count > 0) {
    out += Fold("<table>\n<tr>" + Th("held fixed") + Th("experiment") + Th("unit") + Th("value") +
                    "</tr>\n" +
                    fixed + "</table>\n",
                fixed_count, std::to_string(fixed_count) + " held fixed", 0);
  }
  return out;
}

std::string VelocityTable(const std::vector<ChannelMetrics>& metrics) {
  std::string rows;
  for (const ChannelMetrics& m : metrics) {
    rows += "<tr>" + Td(m.experiment) + Td(m.output) + Num(std::to_string(m.samples)) +
            Num(HtmlNumber(m.mae, "%.4g")) + Num(HtmlNumber(m.rmse, "%.4g")) +
            Num(HtmlNumber(m.r2, "%.5f")) + "</tr>\n";
  }
  return "<table>\n<tr>" + Th("prediction") + Th("state") + Th("samples") + Th("MAE") + Th("RMSE") +
         Th("R²") + "</tr>\n" + rows + "</table>\n";
}

std::string StepRegressionTables(const StepRegressionReport& report) {
  std::string rows;
  for (const TermRegression& t : report.terms) {
    const bool has_best =
        t.path.best >= 0 && t.path.best < static_cast<int>(t.path.cv_error.size());
    const bool asymptote = !t.asymptote_grid.empty();
    rows += "<tr>" + Td(t.name) + Num(HtmlNumber(t.lambda, "%.4g")) +
            Num(asymptote ? HtmlNumber(t.a, "%.4g") : "—") +
            Num(asymptote ? HtmlNumber(t.b, "%.4g") : "—") +
            Num(has_best ? HtmlNumber(t.path.cv_error[t.path.best], "%.4g") : "—") +
            Num(has_best && t.path.best < static_cast<int>(t.path.cv_standard_error.size())
                    ? HtmlNumber(t.path.cv_standard_error[t.path.best], "%.3g")
                    : "—") +
            Num(has_best && t.path.best < static_cast<int>(t.path.nonzero.size())
                    ? std::to_string(t.path.nonzero[t.path.best])
                    : "—") +
            Num(HtmlNumber(t.r2, "%.4f")) + Num(HtmlNumber(t.rms, "%.4g")) +
            Num(std::to_string(t.samples)) + Num(std::to_string(t.groups)) +
            Num(HtmlNumber(t.seconds, "%.3f")) + "</tr>\n";
  }
  const StepSamples& s = report.samples;
  std::string out = "<table>\n<tr>" + Th("term") + Th("λ") + Th("a") + Th("b") + Th("CV error") +
                    Th("CV std. error") + Th("nonzero") + Th("R²") + Th("RMS") + Th("samples") +
                    Th("groups") + Th("time [s]") + "</tr>\n" + rows + "</table>\n";
  out += "<p>" + std::to_string(s.intervals) + " constant-input intervals, " +
         std::to_string(s.steady) + " steady, " + std::to_string(s.steps) +
         " single-input steps; " + std::to_string(s.damping.size()) + " damping samples, " +
         std::to_string(s.inertia[0].size()) + " + " + std::to_string(s.inertia[1].size()) +
         " inertia samples. Time: steady windows " + HtmlNumber(s.window_seconds, "%.3f") +
         " s, step fits " + HtmlNumber(s.fit_seconds, "%.3f") + " s, lasso cross-validation " +
         HtmlNumber(report.regression_seconds, "%.3f") + " s.</p>\n";
  if (!s.notes.empty()) {
    out += "<ul class=\"notes\">\n";
    for (const std::string& note : s.notes) out += "<li>" + HtmlEscape(note) + "</li>\n";
    out += "</ul>\n";
  }
  return out;
}

}  // namespace vesselid

// The tables identification papers print (report_tables.h): parameters by stage as in the
// staged-identification paper's parameter table, per-test cost sqrt(mean e^2) with fit % per
// output, and validation fit % per held-out experiment, per stage and final.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "engine/report/report_table_cells.h"
#include "engine/report/report_tables.h"

namespace vesselid {
namespace {

constexpr size_t kPaperOpenRows = 60;

std::string ValueWithError(double value, double std_error, bool undetermined) {
  std::string text = HtmlNumber(value, "%.5g");
  if (undetermined) return text + " (undetermined)";
  if (std::isfinite(std_error)) text += " ± " + HtmlNumber(std_error, "%.2g");
  return text;
}

// Columns in order of first appearance, and each row's cells by column.
struct SparseTable {
  std::vector<std::string> columns;
  std::vector<std::string> rows;
  std::map<std::string, std::map<std::string, std::string>> cells;

  void Set(const std::string& row, const std::string& column, const std::string& text) {
    if (std::find(columns.begin(), columns.end(), column) == columns.end()) {
      columns.push_back(column);
    }
    if (cells.count(row) == 0) rows.push_back(row);
    cells[row][column] = text;
  }

  // The table, rows keyed "first\nsecond": two heading columns, then one per column.
  std::string Html(const std::string& first, const std::string& second) const {
    std::string text = "<div class=\"scroll\"><table class=\"paper\">\n<tr>" + Th(first) +
                       Th(second);
    for (const std::string& c : columns) text += Th(c);
    text += "</tr>\n";
    for (const std::string& row : rows) {
      const size_t cut = row.find('\n');
      text += "<tr>" + Td(row.substr(0, cut)) + Td(row.substr(cut + 1));
      const std::map<std::string, std::string>& line = cells.at(row);
      for (const std::string& c : columns) {
        const auto at = line.find(c);
        text += at == line.end() ? "<td></td>" : Num(at->second);
      }
      text += "</tr>\n";
    }
    return text + "</table></div>\n";
  }
};

// "per run (12): -0.05 to 0.04": a per-experiment parameter's values in a stage, or the
// final ones.
std::string PerRunRange(const StageResult& stage, const std::string& name,
                        const FinalParameter* final_value = nullptr) {
  int runs = 0;
  double low = 0.0, high = 0.0;
  if (final_value != nullptr) {
    runs = final_value->runs;
    low = final_value->runs_min;
    high = final_value->runs_max;
  } else {
    for (const Estimate& e : stage.estimates) {
      if (e.experiment.empty() || e.kind != EstimateKind::kParameter ||
          e.name.substr(0, e.name.find('[')) != name) {
        continue;
      }
      low = runs == 0 ? e.value : std::min(low, e.value);
      high = runs == 0 ? e.value : std::max(high, e.value);
      ++runs;
    }
  }
  return "per run (" + std::to_string(runs) + "): " + HtmlNumber(low, "%.4g") + " to " +
         HtmlNumber(high, "%.4g");
}

std::string ParametersByStage(const RunConfig& config, const RunResult& result) {
  // Per stage with estimates: the shared estimates by name, and per-experiment parameters.
  std::vector<const StageResult*> stages;
  std::vector<std::map<std::string, const Estimate*>> shared;
  std::vector<std::set<std::string>> per_experiment;
  for (const StageResult& stage : result.stages) {
    std::map<std::string, const Estimate*> own;
    std::set<std::string> each;
    for (const Estimate& e : stage.estimates) {
      if (e.kind != EstimateKind::kParameter || e.role == ParameterRole::kFixed) continue;
      if (e.experiment.empty()) {
        own[e.name] = &e;
      } else {
        each.insert(e.name.substr(0, e.name.find('[')));  // "delta_0[run2]" is delta_0's
      }
    }
    if (own.empty() && each.empty()) continue;
    stages.push_back(&stage);
    shared.push_back(std::move(own));
    per_experiment.push_back(std::move(each));
  }
  std::map<std::string, const FinalParameter*> final_values;
  for (const FinalParameter& f : result.parameters) final_values[f.name] = &f;

  std::string header = "<tr>" + Th("parameter");
  for (const StageResult* stage : stages) header += Th(stage->name);
  header += Th("final") + Th("rule") + "</tr>\n";
  std::string rows, never;
  size_t count = 0, never_count = 0;
  for (const std::string& name : config.model->info().parameters) {
    std::string row = "<tr>" + Td(name);
    bool estimated = false;
    for (size_t s = 0; s < stages.size(); ++s) {
      const auto at = shared[s].find(name);
      if (at != shared[s].end()) {
        const Estimate& e = *at->second;
        row += Num(ValueWithError(e.value, e.std_error, e.undetermined));
        estimated = true;
      } else if (per_experiment[s].count(name) > 0) {
        row += Td(PerRunRange(*stages[s], name));
        estimated = true;
      } else {
        row += "<td></td>";
      }
    }
    const auto f = final_values.find(name);
    if (!estimated) {
      never += (never.empty() ? "" : ", ") + HtmlEscape(name);
      ++never_count;
      continue;
    }
    if (f != final_values.end() && f->second->runs > 0) {
      row += Td(PerRunRange(*stages.back(), name, f->second)) + Td(f->second->rule);
    } else if (f != final_values.end()) {
      const FinalParameter& p = *f->second;
      row += Num(ValueWithError(p.value, p.std_error, p.undetermined && p.role != ParameterRole::kFixed)) +
             Td(p.rule);
    } else {
      row += "<td></td><td></td>";
    }
    rows += row + "</tr>\n";
    ++count;
  }
  std::string out =
      "<h3 id=\"paper-parameters\">Parameters by stage</h3>\n"
      "<p>Estimate ± standard error of every stage that estimates a parameter; "
      "blank where a stage does not; the final value and how it was made "
      "(fusion rule: " +
      HtmlEscape(FusionRuleToString(config.fusion)) + ").</p>\n";
  out +=
      Fold("<div class=\"scroll\"><table class=\"paper\">\n" + header + rows + "</table></div>\n",
           count, std::to_string(count) + " parameters", kPaperOpenRows);
  if (never_count > 0) {
    out +=
        "<p>Held fixed in every stage (" + std::to_string(never_count) + "): " + never + ".</p>\n";
  }
  return out;
}

std::string CostPerTest(const RunResult& result) {
  SparseTable table;
  std::map<std::string, std::string> stage_of;
  for (const StageResult& stage : result.stages) {
    for (const ExperimentFit& fit : stage.summary.fits) {
      if (!IsSimulationFit(fit)) continue;
      const std::string row = fit.experiment + "\n" + stage.name;
      table.Set(row, "√(mean e²)", HtmlNumber(fit.rms_cost, "%.4g"));
      for (const ChannelMetrics& m : fit.channels) {
        table.Set(row, "fit % " + m.output, HtmlNumber(m.fit_percent, "%.2f"));
      }
    }
  }
  std::string out = "<h3 id=\"paper-cost\">Cost per test</h3>\n";
  if (table.rows.empty()) return out + "<p>No stage simulated its experiments.</p>\n";
  out +=
      "<p>Per identification experiment: the stage that fits it, the cost "
      "√(mean e²) over all compared samples, and the fit % per output.</p>\n";
  return out + Fold(table.Html("experiment", "stage"), table.rows.size(),
                    std::to_string(table.rows.size()) + " experiments", kPaperOpenRows);
}

std::string ValidationFit(const RunResult& result) {
  SparseTable table;
  auto add = [&](const std::string& column, const std::vector<ExperimentFit>& fits) {
    for (const ExperimentFit& fit : fits) {
      if (!IsSimulationFit(fit)) continue;
      for (const ChannelMetrics& m : fit.channels) {
        table.Set(fit.experiment + "\n" + m.output, column, HtmlNumber(m.fit_percent, "%.2f"));
      }
    }
  };
  for (const StageResult& stage : result.stages) add(stage.name, stage.validation);
  add("final", result.final_validation);
  std::string out = "<h3 id=\"paper-validation\">Validation fit %</h3>\n";
  if (table.rows.empty()) return out + "<p>No held-out experiments.</p>\n";
  out +=
      "<p>Fit % of the held-out experiments, simulated with each stage's estimates and with "
      "the final values.</p>\n";
  return out + Fold(table.Html("experiment", "output"), table.rows.size(),
                    std::to_string(table.rows.size()) + " rows", kPaperOpenRows);
}

}  // namespace

std::string PaperTables(const RunConfig& config, const RunResult& result) {
  return ParametersByStage(config, result) + CostPerTest(result) + ValidationFit(result);
}

}  // namespace vesselid

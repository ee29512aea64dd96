#include "engine/output/held_out_parameters_report.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "engine/base/format_numbers.h"
#include "engine/base/json_number.h"
#include "engine/base/nan.h"

namespace vesselid {
namespace {

const ExperimentFit* FindFit(const std::vector<ExperimentFit>& fits, const std::string& name) {
  for (const ExperimentFit& fit : fits) {
    if (fit.experiment == name) return &fit;
  }
  return nullptr;
}

// "psi fit 15.5 % without delta_0, 94.8 % with"
std::string FitPhrase(const std::string& output, double with, double without,
                      const std::string& names) {
  return output + " fit " + FormatFinite("%.1f", without) + " % without " + names + ", " +
         FormatFinite("%.1f", with) + " % with";
}

}  // namespace

HeldOutParametersTable MakeHeldOutParametersTable(const HeldOutParameters& parameters, const std::vector<ExperimentFit>& with) {
  HeldOutParametersTable table;
  for (const ExperimentFit& fit : with) {
    HeldOutRunRow row;
    row.experiment = fit.experiment;
    for (const Estimate& e : parameters.estimates) {
      if (e.experiment == fit.experiment) row.estimates.push_back(&e);
    }
    if (fit.diverged) row.diverged_with = fit.message;
    const ExperimentFit* without = FindFit(parameters.without, fit.experiment);
    if (without != nullptr && without->diverged) row.diverged_without = without->message;
    for (const ChannelMetrics& m : fit.channels) {
      bool known = false;
      for (const std::string& o : table.outputs) known |= o == m.output;
      if (!known) table.outputs.push_back(m.output);
      row.fit[m.output] = {m.fit_percent, kUnknown};
      row.mae[m.output] = {m.mae, kUnknown};
    }
    if (without != nullptr) {
      for (const ChannelMetrics& m : without->channels) {
        row.fit.try_emplace(m.output, kUnknown, kUnknown).first->second.second = m.fit_percent;
        row.mae.try_emplace(m.output, kUnknown, kUnknown).first->second.second = m.mae;
      }
    }
    for (const auto& [output, pair] : row.fit) {
      if (!std::isfinite(pair.first) || !std::isfinite(pair.second)) continue;
      table.mean_fit[output].first += pair.first;
      table.mean_fit[output].second += pair.second;
      ++table.counted[output];
    }
    table.rows.push_back(std::move(row));
  }
  for (auto& [output, sums] : table.mean_fit) {
    sums.first /= table.counted[output];
    sums.second /= table.counted[output];
  }
  return table;
}

std::string HeldOutParameterNames(const HeldOutParameters& parameters) {
  std::string names;
  for (const std::string& p : parameters.parameters) names += (names.empty() ? "" : ", ") + p;
  return names;
}

nlohmann::json HeldOutParametersToJson(const HeldOutParameters& parameters,
                                       const std::vector<ExperimentFit>& with) {
  using nlohmann::json;
  json j = {{"per_experiment", parameters.fitted ? "fit" : "hold"},
            {"parameters", parameters.parameters},
            {"held_at", "training_mean"}};
  if (!parameters.fitted) return j;
  const HeldOutParametersTable table = MakeHeldOutParametersTable(parameters, with);
  json runs = json::array();
  auto pairs = [](const std::map<std::string, std::pair<double, double>>& values) {
    json out = json::object();
    for (const auto& [output, pair] : values) {
      out[output] = {{"with", JsonNumber(pair.first)}, {"without", JsonNumber(pair.second)}};
    }
    return out;
  };
  for (const HeldOutRunRow& row : table.rows) {
    json estimates = json::object();
    for (const Estimate* e : row.estimates) {
      estimates[e->name.substr(0, e->name.find('['))] = {{"value", e->value},
                                                         {"std_error", JsonNumber(e->std_error)},
                                                         {"start", e->start},
                                                         {"lower", JsonNumber(e->lower)},
                                                         {"upper", JsonNumber(e->upper)},
                                                         {"undetermined", e->undetermined}};
    }
    json run = {{"experiment", row.experiment},
                {"estimates", estimates},
                {"fit_percent", pairs(row.fit)},
                {"mae", pairs(row.mae)}};
    if (!row.diverged_with.empty()) run["diverged_with"] = row.diverged_with;
    if (!row.diverged_without.empty()) run["diverged_without"] = row.diverged_without;
    runs.push_back(run);
  }
  j["runs"] = runs;
  j["mean_fit_percent"] = pairs(table.mean_fit);
  return j;
}

std::string HeldOutParametersText(const HeldOutParameters& parameters,
                                  const std::vector<ExperimentFit>& with,
                                  const std::string& indent, const ParameterUnitOf& unit_of) {
  if (!parameters.active()) return "";
  const std::string names = HeldOutParameterNames(parameters);
  if (!parameters.fitted) {
    return indent + "per-experiment parameters (" + names +
           ") held at the training runs' mean on the held-out runs (per_experiment: hold)\n";
  }
  const HeldOutParametersTable table = MakeHeldOutParametersTable(parameters, with);
  std::string out = indent + "held-out runs with their own " + names +
                    " (estimated per run, the other parameters held; per_experiment: fit); "
                    "without: " + names + " held at the training runs' mean:\n";
  for (const HeldOutRunRow& row : table.rows) {
    std::string line = indent + "  " + row.experiment + ":";
    for (const Estimate* e : row.estimates) {
      const DisplayUnit unit = unit_of ? unit_of(e->name) : DisplayUnit{};
      line += " " + e->name.substr(0, e->name.find('[')) + " = " +
              FormatFinite("%.6g", unit.scale * e->value) +
              (e->undetermined ? " (undetermined)"
                               : " ± " + FormatFinite("%.2g", unit.scale * e->std_error)) +
              (unit.unit.empty() ? "" : " " + unit.unit) + ";";
    }
    for (const std::string& output : table.outputs) {
      const auto at = row.fit.find(output);
      if (at == row.fit.end()) continue;
      line += " " + FitPhrase(output, at->second.first, at->second.second, names) + ";";
    }
    if (!row.diverged_with.empty()) line += " with: " + row.diverged_with + ";";
    if (!row.diverged_without.empty()) line += " without: " + row.diverged_without + ";";
    line.pop_back();
    out += line + "\n";
  }
  for (const std::string& output : table.outputs) {
    const auto at = table.mean_fit.find(output);
    if (at == table.mean_fit.end()) continue;
    out += indent + "  mean over " + std::to_string(table.counted.at(output)) +
           " held-out run(s): " + FitPhrase(output, at->second.first, at->second.second, names) +
           "\n";
  }
  return out;
}

}  // namespace vesselid

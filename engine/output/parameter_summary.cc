#include "engine/output/parameter_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace vesselid {
namespace {

std::string Number6(double value) {
  char text[48];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

}  // namespace

std::vector<ParameterReport> ReportParameters(const RunResult& result) {
  std::vector<ParameterReport> reports;
  for (const FinalParameter& f : result.parameters) {
    ParameterReport r;
    r.name = f.name;
    // The stages' shared estimates of it, in stage order.
    std::vector<const Estimate*> estimates;
    std::vector<std::string> stage_names;
    for (const StageResult& stage : result.stages) {
      if (std::find(f.stages.begin(), f.stages.end(), stage.name) == f.stages.end()) continue;
      for (const Estimate& e : stage.estimates) {
        if (e.kind == EstimateKind::kParameter && e.name == f.name && e.experiment.empty() &&
            e.role != ParameterRole::kFixed) {
          estimates.push_back(&e);
          stage_names.push_back(stage.name);
        }
      }
    }
    if (f.role != ParameterRole::kFixed && !estimates.empty()) {
      r.lower = estimates.back()->lower;
      r.upper = estimates.back()->upper;
      r.bound = BoundSide(f.value, r.lower, r.upper);
    } else if (f.runs > 0 && !f.stages.empty()) {
      // Per experiment: the bounds its per-run values had in the last stage that estimated it
      // ("delta_0[zz1]", ...; one set of bounds for every run).
      for (const StageResult& stage : result.stages) {
        if (stage.name != f.stages.back()) continue;
        for (const Estimate& e : stage.estimates) {
          if (e.kind != EstimateKind::kParameter || e.experiment.empty() ||
              e.name.compare(0, f.name.size() + 1, f.name + "[") != 0) {
            continue;
          }
          r.lower = e.lower;
          r.upper = e.upper;
        }
      }
    }
    if (std::isfinite(f.std_error) && !f.undetermined && f.role != ParameterRole::kFixed) {
      const double low = f.value - 1.96 * f.std_error, high = f.value + 1.96 * f.std_error;
      r.interval_low = std::max(low, r.lower);
      r.interval_high = std::min(high, r.upper);
      r.clipped = low < r.lower || high > r.upper;
    }
    if (estimates.size() >= 2) {
      double low = estimates.front()->value, high = low;
      for (const Estimate* e : estimates) {
        low = std::min(low, e->value);
        high = std::max(high, e->value);
      }
      const double slack = 1e-9 * std::max(1.0, std::abs(high));
      if (f.value < low - slack || f.value > high + slack) {
        std::string list;
        for (size_t k = 0; k < estimates.size(); ++k) {
          list += (k ? ", " : "") + Number6(estimates[k]->value) + " in " + stage_names[k];
        }
        r.fusion_note = f.name + " = " + Number6(f.value) +
                        " lies outside every stage's estimate (" + list + "): " + f.rule +
                        " fusion solves for all shared parameters at once with each stage's "
                        "covariance, so it moves with the parameters it is correlated with";
      }
    }
    reports.push_back(r);
  }
  return reports;
}

std::string ParameterFlags(const ParameterReport& report, const std::string& unit) {
  std::string flags;
  if (report.bound != 0) {
    flags = std::string("on its ") + (report.bound < 0 ? "lower" : "upper") + " bound " +
            Number6(report.bound < 0 ? report.lower : report.upper) +
            (unit.empty() ? "" : " " + unit);
  }
  if (report.clipped)
    flags += (flags.empty() ? "" : "; ") + std::string("interval clipped to the bounds");
  return flags;
}

UnknownCounts CountUnknowns(const std::vector<Estimate>& estimates) {
  UnknownCounts counts;
  std::set<std::string> per_experiment, fixed;
  for (const Estimate& e : estimates) {
    if (e.kind == EstimateKind::kInitialState) {
      if (e.role != ParameterRole::kFixed) ++counts.initial_states;
      continue;
    }
    if (e.role == ParameterRole::kFixed) {
      fixed.insert(e.name);
    } else if (e.role == ParameterRole::kPerExperiment || !e.experiment.empty()) {
      per_experiment.insert(e.name);
      ++counts.per_experiment_values;
    } else {
      ++counts.shared;
    }
  }
  counts.per_experiment = static_cast<int>(per_experiment.size());
  counts.fixed = static_cast<int>(fixed.size());
  return counts;
}

UnknownCounts CountUnknowns(const RunResult& result) {
  UnknownCounts counts;
  for (const FinalParameter& f : result.parameters) {
    if (f.role == ParameterRole::kFixed) {
      ++counts.fixed;
    } else if (f.role == ParameterRole::kPerExperiment) {
      ++counts.per_experiment;
    } else {
      ++counts.shared;
    }
  }
  for (const StageResult& stage : result.stages) {
    const UnknownCounts s = CountUnknowns(stage.estimates);
    counts.initial_states += s.initial_states;
    counts.per_experiment_values += s.per_experiment_values;
  }
  return counts;
}

std::string DescribeCounts(const UnknownCounts& c) {
  std::string text = std::to_string(c.shared + c.per_experiment) + " parameter" +
                     (c.shared + c.per_experiment == 1 ? "" : "s") + " estimated";
  if (c.per_experiment > 0) {
    text += " (" + std::to_string(c.shared) + " shared, " + std::to_string(c.per_experiment) +
            " per experiment: " + std::to_string(c.per_experiment_values) + " values)";
  }
  text += ", " + std::to_string(c.fixed) + " held fixed; " + std::to_string(c.initial_states) +
          " initial state" + (c.initial_states == 1 ? "" : "s") + " estimated";
  return text;
}

}  // namespace vesselid

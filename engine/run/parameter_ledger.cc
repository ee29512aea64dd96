#include "engine/run/parameter_ledger.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "engine/base/nan.h"

namespace vesselid {
namespace {

// Information fusion of every parameter that is shared in its last estimating stage and
// determined by at least one stage, with each stage's covariance block of the shared
// parameters it determined. False if a stage has no covariance or the fusion is singular.
bool FuseSharedJointly(const ParameterLedger& ledger, const std::vector<StageResult>& stages,
                       std::map<std::string, std::pair<double, double>>* fused) {
  std::vector<std::string> names;
  for (const auto& [name, entries] : ledger.estimates) {
    bool determined = false;
    for (const ParameterLedger::Entry& e : entries) determined |= std::isfinite(e.std_error);
    if (entries.back().role == ParameterRole::kShared && determined) names.push_back(name);
  }
  if (names.empty()) return true;
  auto position = [&](const std::string& name) {
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  std::vector<SharedEstimate> estimates;
  for (const StageResult& stage : stages) {
    std::vector<const Estimate*> shared;
    for (const Estimate& e : stage.estimates) {
      if (e.kind == EstimateKind::kParameter && e.role == ParameterRole::kShared &&
          e.experiment.empty() && position(e.name) < static_cast<int>(names.size()) &&
          !e.undetermined && std::isfinite(e.std_error)) {
        shared.push_back(&e);
      }
    }
    if (shared.empty()) continue;
    std::vector<int> row;  // each estimate's row in the stage's correlation matrix
    for (const Estimate* e : shared) {
      const auto& c = stage.correlation_names;
      const auto found = std::find(c.begin(), c.end(), e->name);
      if (found == c.end()) return false;
      row.push_back(static_cast<int>(found - c.begin()));
    }
    SharedEstimate estimate;
    const int m = static_cast<int>(shared.size());
    estimate.value.resize(m);
    estimate.covariance.resize(m, m);
    for (int i = 0; i < m; ++i) {
      estimate.parameters.push_back(position(shared[i]->name));
      estimate.value[i] = shared[i]->value;
      for (int j = 0; j < m; ++j) {
        estimate.covariance(i, j) =
            stage.correlation(row[i], row[j]) * shared[i]->std_error * shared[j]->std_error;
      }
    }
    estimates.push_back(std::move(estimate));
  }
  Eigen::VectorXd value;
  Eigen::MatrixXd covariance;
  if (!FuseJointly(static_cast<int>(names.size()), estimates, &value, &covariance)) return false;
  for (size_t i = 0; i < names.size(); ++i) {
    (*fused)[names[i]] = {value[i], std::sqrt(covariance(i, i))};
  }
  return true;
}

// A parameter estimated per experiment: its values in the last stage that estimated it
// (count and range) and their mean, which a run without its own value takes (a held-out run
// starts from it; predict, export and Python simulate with it), within the stage's bounds.
void PerExperimentFinal(const std::vector<StageResult>& stages, FinalParameter* f) {
  for (const StageResult& stage : stages) {
    int runs = 0;
    double low = 0.0, high = 0.0, sum = 0.0, lower = -INFINITY, upper = INFINITY;
    for (const Estimate& e : stage.estimates) {
      if (e.kind != EstimateKind::kParameter || e.role != ParameterRole::kPerExperiment ||
          e.experiment.empty() || e.name.substr(0, e.name.find('[')) != f->name) {
        continue;
      }
      low = runs == 0 ? e.value : std::min(low, e.value);
      high = runs == 0 ? e.value : std::max(high, e.value);
      sum += e.value;
      lower = e.lower;
      upper = e.upper;
      ++runs;
    }
    if (runs == 0) continue;
    f->role = ParameterRole::kPerExperiment;
    f->rule = "per_experiment";
    f->stages = {stage.name};
    f->value = std::clamp(sum / runs, lower, upper);
    f->runs = runs;
    f->runs_min = low;
    f->runs_max = high;
  }
}

}  // namespace

bool ResolveParameters(const StageConfig& stage, const ModelInfo& info,
                       const ParameterLedger& ledger, std::vector<ParameterSpec>* specs,
                       std::string* error) {
  specs->clear();
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    const std::string& name = info.parameters[i];
    auto latest = ledger.latest.find(name);
    const double carried =
        latest != ledger.latest.end() ? latest->second : info.parameter_defaults[i];
    ParameterSpec spec;
    bool listed = false;
    for (const ParameterSpec& s : stage.parameters) {
      if (s.name == name) {
        spec = s;
        listed = true;
      }
    }
    if (!listed) {
      spec.name = name;
      spec.role = ParameterRole::kFixed;
      spec.start = carried;
    }
    auto bounds = ledger.bounds.find(name);
    if (listed && spec.role != ParameterRole::kFixed && bounds != ledger.bounds.end()) {
      if (!std::isfinite(spec.lower)) spec.lower = bounds->second.first;
      if (!std::isfinite(spec.upper)) spec.upper = bounds->second.second;
    }
    auto per_experiment = ledger.per_experiment.find(name);
    if (listed && spec.start_from_previous && spec.role == ParameterRole::kPerExperiment &&
        per_experiment != ledger.per_experiment.end()) {
      spec.experiment_starts = per_experiment->second;
    }
    if (listed && spec.start_from_previous) {
      spec.start = carried;
      spec.start_from_previous = false;
      if (spec.role != ParameterRole::kFixed && (carried < spec.lower || carried > spec.upper)) {
        *error = "parameter '" + name + "': carried start " + std::to_string(carried) +
                 " is outside the stage's bounds [" + std::to_string(spec.lower) + ", " +
                 std::to_string(spec.upper) + "]";
        return false;
      }
    }
    specs->push_back(spec);
  }
  return true;
}

void RecordStartValues(const StageResult& stage, ParameterLedger* ledger) {
  for (const Estimate& e : stage.estimates) {
    if (e.kind != EstimateKind::kParameter || e.role == ParameterRole::kPerExperiment) continue;
    ledger->latest[e.name] = e.start;
  }
}

void RecordStageOrItsBaseline(const StageResult& stage, ParameterLedger* ledger) {
  if (stage.rejected.empty()) {
    RecordStage(stage, ledger);
  } else if (stage.held_out.baseline != "previous") {
    RecordStartValues(stage, ledger);
  }  // set aside against the previous stages' values: the ledger holds them already
}

void RecordStage(const StageResult& stage, ParameterLedger* ledger) {
  for (const Estimate& e : stage.estimates) {
    if (e.kind == EstimateKind::kParameter && e.role == ParameterRole::kPerExperiment &&
        !e.experiment.empty()) {
      ledger->per_experiment[e.name.substr(0, e.name.find('['))][e.experiment] = e.value;
    }
    if (e.kind != EstimateKind::kParameter || !e.experiment.empty()) continue;
    if (!IsEstimatedOnce(e.role)) continue;
    ledger->latest[e.name] = e.value;
    ledger->bounds[e.name] = {e.lower, e.upper};
    ledger->estimates[e.name].push_back(
        {stage.name, e.value, e.undetermined ? kUnknown : e.std_error, e.role});
  }
}

std::vector<FinalParameter> FinalParameters(const ModelInfo& info, const ParameterLedger& ledger,
                                            const std::vector<StageResult>& stages,
                                            FusionRule rule) {
  std::map<std::string, std::pair<double, double>> joint;
  const bool joint_ok =
      rule == FusionRule::kInformation && FuseSharedJointly(ledger, stages, &joint);
  std::vector<FinalParameter> parameters;
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    FinalParameter f;
    f.name = info.parameters[i];
    auto found = ledger.estimates.find(f.name);
    if (found == ledger.estimates.end()) {
      auto latest = ledger.latest.find(f.name);
      f.value = latest != ledger.latest.end() ? latest->second : info.parameter_defaults[i];
      // The value a fixed parameter was held at in the last stage.
      for (const StageResult& s : stages) {
        for (const Estimate& e : s.estimates) {
          if (e.name == f.name) f.value = e.value;
        }
      }
      f.std_error = kUnknown;
      f.role = ParameterRole::kFixed;
      f.rule = "fixed";
      PerExperimentFinal(stages, &f);
      parameters.push_back(f);
      continue;
    }
    const std::vector<ParameterLedger::Entry>& entries = found->second;
    const ParameterLedger::Entry& last = entries.back();
    f.role = last.role;
    if (last.role == ParameterRole::kShared) {
      std::vector<double> values, errors;
      for (const ParameterLedger::Entry& e : entries) {
        if (e.role != ParameterRole::kShared) continue;
        values.push_back(e.value);
        errors.push_back(e.std_error);
        f.stages.push_back(e.stage);
      }
      if (joint_ok && joint.count(f.name) > 0) {
        std::tie(f.value, f.std_error) = joint.at(f.name);
        f.rule = "information";
      } else {
        FuseEstimates(values, errors, rule, &f.value, &f.std_error, &f.rule);
        if (rule == FusionRule::kInformation && !joint_ok) f.rule += " (information singular)";
      }
    } else {
      f.value = last.value;
      f.std_error = last.std_error;
      f.stages = {last.stage};
      f.rule = "stage";
    }
    f.undetermined = std::isnan(f.std_error);
    parameters.push_back(f);
  }
  return parameters;
}

}  // namespace vesselid

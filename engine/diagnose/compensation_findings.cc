#include "engine/diagnose/compensation_findings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace vesselid {
namespace {

// The stage's reported estimate of a parameter (shared, or one run's value of a
// per-experiment one, "delta_0[zz1]"), or null (initial states).
const Estimate* ParameterEstimateNamed(const StageResult& stage, const std::string& name) {
  for (const Estimate& e : stage.estimates) {
    if (e.kind == EstimateKind::kParameter && e.name == name) return &e;
  }
  return nullptr;
}

// Standard error relative to the value; infinite when either is missing or the value is 0.
double RelativeError(const Estimate& e) {
  const double relative = e.std_error / std::abs(e.value);
  return std::isfinite(relative) ? relative : std::numeric_limits<double>::infinity();
}

std::string Percent(double relative) {
  if (!std::isfinite(relative)) return "no standard error";
  char text[48];
  std::snprintf(text, sizeof(text), "relative standard error %.3g %%", 100.0 * relative);
  return text;
}

}  // namespace

void AddCompensationFindings(const ModelInfo& info, const StageResult& stage,
                             std::vector<Finding>* findings) {
  const Eigen::MatrixXd& c = stage.correlation;
  const int n = static_cast<int>(stage.correlation_names.size());
  if (c.rows() != n || c.cols() != n) return;
  std::vector<const Estimate*> estimate(n);
  for (int i = 0; i < n; ++i) {
    estimate[i] = ParameterEstimateNamed(stage, stage.correlation_names[i]);
  }
  // Groups of estimates linked by compensating pairs (union-find), each reported once.
  std::vector<int> group(n);
  for (int i = 0; i < n; ++i) group[i] = i;
  auto root = [&](int i) {
    while (group[i] != i) i = group[i] = group[group[i]];
    return i;
  };
  std::vector<std::pair<int, int>> pairs;
  std::vector<char> determined;  // per pair: one of the two determined (below)
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (estimate[i] == nullptr || estimate[j] == nullptr) continue;
      if (!(std::abs(c(i, j)) > kCompensationCorrelation)) continue;
      // Both determined to within kCompensationRelativeError despite the correlation: the
      // data separate them (a noise-free record), nothing is doubtful.
      if (std::max(RelativeError(*estimate[i]), RelativeError(*estimate[j])) <
          kCompensationRelativeError) {
        continue;
      }
      pairs.emplace_back(i, j);
      group[root(j)] = root(i);
      // One of the two determined (relative SE below the limit): its standard error already
      // carries the trade-off, and the other's is weakly_determined's to judge. A note.
      determined.push_back(std::min(RelativeError(*estimate[i]), RelativeError(*estimate[j])) <
                           kCompensationRelativeError);
    }
  }
  for (int g = 0; g < n; ++g) {
    if (root(g) != g) continue;
    std::vector<int> members;
    std::pair<int, int> strongest(-1, -1);
    int count = 0;
    bool all_determined = true;
    for (size_t k = 0; k < pairs.size(); ++k) {
      const auto [i, j] = pairs[k];
      if (root(i) != g) continue;
      ++count;
      all_determined &= determined[k] != 0;
      if (strongest.first < 0 ||
          std::abs(c(i, j)) > std::abs(c(strongest.first, strongest.second))) {
        strongest = {i, j};
      }
    }
    if (count == 0) continue;
    for (int i = 0; i < n; ++i) {
      if (root(i) == g && estimate[i] != nullptr) members.push_back(i);
    }
    // The one to drop: the largest relative standard error (the first on ties).
    int drop = members[0];
    for (int i : members) {
      if (RelativeError(*estimate[i]) > RelativeError(*estimate[drop])) drop = i;
    }
    std::string names;
    for (size_t k = 0; k < members.size(); ++k) {
      names += (k == 0                    ? ""
                : k + 1 == members.size() ? " and "
                                          : ", ") +
               estimate[members[k]]->name;
    }
    const auto [a, b] = strongest;
    char text[200];
    if (members.size() == 2) {
      std::snprintf(text, sizeof(text), " compensate each other (correlation %+.4f)", c(a, b));
    } else {
      std::snprintf(text, sizeof(text),
                    " compensate each other (%d pairs above |correlation| 0.999, strongest "
                    "%s/%s %+.4f)",
                    count, estimate[a]->name.c_str(), estimate[b]->name.c_str(), c(a, b));
    }
    std::string line = names + text + ": the data determine only " +
                       (members.size() == 2 ? "their combination" : "combinations of them") +
                       "; drop or fix " + estimate[drop]->name + " (" +
                       Percent(RelativeError(*estimate[drop])) + ")";
    if (members.size() == 2) {
      const int keep = drop == members[0] ? members[1] : members[0];
      line.pop_back();
      line += "; " + estimate[keep]->name + ": " + Percent(RelativeError(*estimate[keep])) + ")";
    }
    std::string hint;
    for (int i : members) {
      const auto it = info.compensation_hints.find(estimate[i]->name);
      if (it != info.compensation_hints.end()) {
        hint = it->second;
        break;
      }
    }
    if (!hint.empty()) line += "; " + hint;
    Finding f = MakeFinding(FindingKind::kCompensation, line);
    f.stage = stage.name;
    f.parameter = names;
    f.value = c(a, b);
    f.threshold = kCompensationCorrelation;
    if (all_determined) {
      f.severity = FindingSeverity::kInfo;
      int best = members[0];  // the best determined
      for (int i : members) {
        if (RelativeError(*estimate[i]) < RelativeError(*estimate[best])) best = i;
      }
      f.message += "; " + estimate[best]->name +
                   " is determined all the same: its standard error includes the trade-off";
    }
    findings->push_back(std::move(f));
  }
}

std::string StructureHint(const ModelInfo& info, const std::string& parameter) {
  const auto it = info.compensation_hints.find(parameter);
  return it == info.compensation_hints.end() ? "" : " (" + it->second + ")";
}

}  // namespace vesselid

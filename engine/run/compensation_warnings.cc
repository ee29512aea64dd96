#include "engine/run/compensation_warnings.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace vesselid {
namespace {

// The stage's reported estimate of a shared parameter, or null (initial states,
// per-experiment values).
const Estimate* ParameterEstimateNamed(const StageResult& stage, const std::string& name) {
  for (const Estimate& e : stage.estimates) {
    if (e.kind == EstimateKind::kParameter && e.experiment.empty() && e.name == name) return &e;
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

std::string Hint(const ModelInfo& info, const std::string& a, const std::string& b) {
  for (const std::string* name : {&a, &b}) {
    const auto it = info.compensation_hints.find(*name);
    if (it != info.compensation_hints.end()) return it->second;
  }
  return "";
}

}  // namespace

void AddCompensationWarnings(const ModelInfo& info, const StageResult& stage,
                             const std::string& where, std::vector<std::string>* warnings) {
  const Eigen::MatrixXd& c = stage.correlation;
  const int n = static_cast<int>(stage.correlation_names.size());
  if (c.rows() != n || c.cols() != n) return;
  int found = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (!(std::abs(c(i, j)) > kCompensationCorrelation)) continue;
      const Estimate* a = ParameterEstimateNamed(stage, stage.correlation_names[i]);
      const Estimate* b = ParameterEstimateNamed(stage, stage.correlation_names[j]);
      if (a == nullptr || b == nullptr) continue;
      if (++found > kMaxCompensationWarnings) continue;
      const double ra = RelativeError(*a), rb = RelativeError(*b);
      const Estimate* drop = ra >= rb ? a : b;
      const Estimate* keep = drop == a ? b : a;
      char text[160];
      std::snprintf(text, sizeof(text), "%s and %s compensate each other (correlation %+.4f)",
                    a->name.c_str(), b->name.c_str(), c(i, j));
      std::string line = where + text +
                         ": the data determine only their combination; drop or fix " +
                         drop->name + " (" + Percent(RelativeError(*drop)) + "; " +
                         keep->name + ": " + Percent(RelativeError(*keep)) + ")";
      const std::string hint = Hint(info, a->name, b->name);
      if (!hint.empty()) line += "; " + hint;
      warnings->push_back(line);
    }
  }
  if (found > kMaxCompensationWarnings) {
    warnings->push_back(where + std::to_string(found - kMaxCompensationWarnings) +
                        " more pair(s) of estimates compensate each other (|correlation| > "
                        "0.999): see the correlation matrix");
  }
}

std::string StructureHint(const ModelInfo& info, const std::string& note) {
  const size_t end = note.find(' ');
  if (end == std::string::npos) return "";
  const auto it = info.compensation_hints.find(note.substr(0, end));
  return it == info.compensation_hints.end() ? "" : " (" + it->second + ")";
}

}  // namespace vesselid

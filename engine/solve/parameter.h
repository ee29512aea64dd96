// Named model parameters as a run declares them: start value, bounds, scale and role.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace vesselid {

enum class ParameterRole {
  kFree,           // one value estimated from every experiment of the stage
  kFixed,          // held at its start value
  kPerExperiment,  // estimated, one value per experiment (e.g. a rudder bias per run)
  // In a staged run (seed 002): estimated like kFree; an isolated parameter is final after
  // its stage, a shared one starts the next stage and is fused over all its stages at the end.
  kIsolated,
  kShared,
};

// True for the roles the solver estimates as one shared block.
inline bool IsEstimatedOnce(ParameterRole role) {
  return role == ParameterRole::kFree || role == ParameterRole::kIsolated ||
         role == ParameterRole::kShared;
}

const char* ParameterRoleToString(ParameterRole role);
bool StringToParameterRole(const std::string& text, ParameterRole* role);

// Which bound `value` is on: -1 lower, +1 upper, 0 neither (or no finite bound). Tolerance:
// 1e-6 of the bound range, of max(1, |bound|) when the other bound is infinite.
inline int BoundSide(double value, double lower, double upper) {
  const bool finite = std::isfinite(lower) && std::isfinite(upper);
  auto tolerance = [&](double bound) {
    return 1e-6 * (finite ? upper - lower : std::max(1.0, std::abs(bound)));
  };
  if (std::isfinite(lower) && value - lower <= tolerance(lower)) return -1;
  if (std::isfinite(upper) && upper - value <= tolerance(upper)) return 1;
  return 0;
}

struct ParameterSpec {
  std::string name;
  double start = 0.0;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  // The solver works on theta = value / scale. 0 means |start|, or 1 if start is 0.
  double scale = 0.0;
  ParameterRole role = ParameterRole::kFree;
  // The start is the latest estimate of an earlier stage (or the model default) rather than
  // `start`; resolved by the pipeline before the problem is built.
  bool start_from_previous = false;
  // kPerExperiment: starts of particular experiments (by name, or by the record a segment or
  // piece comes from), e.g. an earlier stage's per-experiment estimates; others start at
  // `start`.
  std::map<std::string, double> experiment_starts = {};

  double EffectiveScale() const;
  // Bounds ordered, start finite and inside them, scale positive. `where` prefixes messages.
  bool IsValid(const std::string& where, std::string* error) const;
};

}  // namespace vesselid

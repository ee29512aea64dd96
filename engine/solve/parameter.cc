#include "engine/solve/parameter.h"

#include <cmath>
#include <sstream>

namespace vesselid {

const char* ParameterRoleToString(ParameterRole role) {
  switch (role) {
    case ParameterRole::kFree:
      return "free";
    case ParameterRole::kFixed:
      return "fixed";
    case ParameterRole::kPerExperiment:
      return "per_experiment";
    case ParameterRole::kIsolated:
      return "isolated";
    case ParameterRole::kShared:
      return "shared";
  }
  return "unknown";
}

bool StringToParameterRole(const std::string& text, ParameterRole* role) {
  for (ParameterRole candidate :
       {ParameterRole::kFree, ParameterRole::kFixed, ParameterRole::kPerExperiment,
        ParameterRole::kIsolated, ParameterRole::kShared}) {
    if (text == ParameterRoleToString(candidate)) {
      *role = candidate;
      return true;
    }
  }
  return false;
}

double ParameterSpec::EffectiveScale() const {
  if (scale > 0.0) return scale;
  return start != 0.0 ? std::abs(start) : 1.0;
}


bool ParameterSpec::IsValid(const std::string& where, std::string* error) const {
  std::ostringstream message;
  message << where << ": parameter '" << name << "': ";
  if (!start_from_previous && !std::isfinite(start)) {
    message << "start is not finite";
  } else if (std::isnan(lower) || std::isnan(upper) || !(lower < upper)) {
    message << "bounds inverted or empty (lower " << lower << " >= upper " << upper << ")";
  } else if (!start_from_previous && (start < lower || start > upper)) {
    message << "start " << start << " outside bounds [" << lower << ", " << upper << "]";
  } else if (scale < 0.0 || !std::isfinite(scale)) {
    message << "scale must be positive";
  } else {
    return true;
  }
  *error = message.str();
  return false;
}

}  // namespace vesselid

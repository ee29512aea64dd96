// Numbers in results JSON: NaN and infinities (an unknown standard error, an undetermined
// condition number) are written as null and read back as a fallback.
#pragma once

#include <cmath>

#include "nlohmann/json.hpp"

namespace vesselid {

inline nlohmann::json JsonNumber(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

inline double NumberOr(const nlohmann::json& value, double fallback) {
  return value.is_number() ? value.get<double>() : fallback;
}

}  // namespace vesselid

// Whether every one of n values is finite (the vessel simulators' guard on states and rates).
#pragma once

#include <cmath>

namespace vesselid::input_gain {

inline bool AllFinite(const double* x, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) return false;
  }
  return true;
}

}  // namespace vesselid::input_gain

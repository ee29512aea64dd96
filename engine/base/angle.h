// Angles: differences of headings and other angles wrapped to one turn.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace vesselid {

// An angle difference wrapped to (-pi, pi].
inline double WrapAngle(double a) { return a - 2.0 * M_PI * std::round(a / (2.0 * M_PI)); }

// Makes a sampled angle continuous: each step taken as the shorter way round. Returns the
// largest step taken (a step near pi cannot be told from one the other way).
inline double UnwrapAngles(std::vector<double>* angle) {
  double largest = 0.0;
  for (size_t k = 1; k < angle->size(); ++k) {
    const double step = WrapAngle((*angle)[k] - (*angle)[k - 1]);
    (*angle)[k] = (*angle)[k - 1] + step;
    largest = std::max(largest, std::abs(step));
  }
  return largest;
}

}  // namespace vesselid

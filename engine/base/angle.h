// Angles: differences of headings and other angles wrapped to one turn.
#pragma once

#include <cmath>

namespace vesselid {

// An angle difference wrapped to (-pi, pi].
inline double WrapAngle(double a) { return a - 2.0 * M_PI * std::round(a / (2.0 * M_PI)); }

}  // namespace vesselid

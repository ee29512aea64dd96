// The quiet NaN that marks a missing or undefined value (a sample not recorded, a figure that
// cannot be computed).
#pragma once

#include <limits>

namespace vesselid {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// An estimate, standard error or figure that is not known.
inline constexpr double kUnknown = kNaN;

}  // namespace vesselid

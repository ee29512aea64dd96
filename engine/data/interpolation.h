// Input interpolation between recorded samples of one channel.
//   zero_order_hold: u(t) = u_k for t_k <= t < t_k+1 (switched commands)
//   linear:          straight line between neighbouring samples
//   cubic:           cubic Hermite with Catmull-Rom slopes m_k = (u_k+1 - u_k-1)/(t_k+1 - t_k-1)
// Outside the sampled span the end values are held.
#pragma once

#include <string>
#include <vector>

#include "engine/data/trajectory.h"

namespace vesselid {

enum class Interpolation { kZeroOrderHold, kLinear, kCubic };

const char* InterpolationToString(Interpolation interpolation);
bool StringToInterpolation(const std::string& text, Interpolation* interpolation);

// Values of `channel` at the increasing times `times` (one forward sweep, O(n + m)).
// With `left_limit`, a zero-order hold takes the value before a switch at exactly a sample
// time (the end of an integration step that ends on a switch must not see the new value).
std::vector<double> InterpolateAt(const Channel& channel, Interpolation interpolation,
                                  const std::vector<double>& times, bool left_limit = false);

}  // namespace vesselid

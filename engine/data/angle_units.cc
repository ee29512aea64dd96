#include "engine/data/angle_units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesselid {

AngleUnitCheck CheckAngleUnit(const std::vector<double>& values) {
  constexpr double kTurn = 2.0 * M_PI + 1e-6;
  AngleUnitCheck check;
  bool any = false, step_outside_turn = false;
  double previous = 0.0, anchor = 0.0, travel = 0.0;
  int direction = 0, reversals = 0;  // of the counted moves
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    if (!any) {
      check.min = check.max = previous = anchor = v;
      any = true;
      continue;
    }
    const double step = std::abs(v - previous);
    check.largest_step = std::max(check.largest_step, step);
    if (step > M_PI && (std::abs(v) > kTurn || std::abs(previous) > kTurn)) {
      step_outside_turn = true;
    }
    if (std::abs(v - anchor) > kSwingBand) {
      travel += std::abs(v - anchor);
      const int sign = v > anchor ? 1 : -1;
      reversals += direction != 0 && sign != direction;
      direction = sign;
      anchor = v;
    }
    check.min = std::min(check.min, v);
    check.max = std::max(check.max, v);
    previous = v;
  }
  const double range = check.max - check.min;
  check.looks_like_degrees = step_outside_turn || (range > kTurn && travel > 1.5 * range &&
                                                   reversals >= kSwingReversals);
  return check;
}

std::string DescribeDegreesLook(const std::string& column, const AngleUnitCheck& check) {
  char text[256];
  std::snprintf(text, sizeof(text),
                "column '%s' looks like degrees: range %.4g–%.4g, steps up to %.3g; add it to "
                "degrees:",
                column.c_str(), check.min, check.max, check.largest_step);
  return text;
}

}  // namespace vesselid

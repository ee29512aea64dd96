// How a record's sample intervals are cut into RK4 steps, one rule for the run's experiments
// (experiment.h) and every other simulation of a record (open_loop_simulation.h): equal steps
// of at most the step bound per interval, the bound `max_step` or, when that is 0, the
// record's (upper) median sample interval.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/base/statistics.h"

namespace vesselid {

inline double StepBound(const std::vector<double>& intervals, double max_step) {
  return max_step > 0 ? max_step : UpperMedian(intervals, 0.0);
}

// Steps in an interval of length `interval` under `bound` (at least one; a step a hair over
// the bound by rounding is not split).
inline double StepsIn(double interval, double bound) {
  return std::max(1.0, std::ceil(interval / bound - 1e-6));
}

}  // namespace vesselid

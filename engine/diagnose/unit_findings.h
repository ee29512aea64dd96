// Units a run doubts (unit_suspect findings naming the experiment and the column):
//   * an angle output whose column is not listed in the experiment's `degrees:` but looks like
//     degrees (angle_units.h): read as radians such a heading runs to nonsense while a wrapped
//     residual stays below pi;
//   * an angle input (a rudder, unit rad) not listed in `degrees:` that goes beyond
//     kMaxAngleInput: no rudder or fin turns that far, a rudder logged in degrees does;
//   * a time column whose median sample interval is above kMaxSampleInterval or below
//     kMinSampleInterval: a ship's motion is logged at 0.01-10 s, a time in milliseconds read
//     as seconds at 10-1000 s, one in seconds read as milliseconds at 0.01-1 ms.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"

namespace vesselid {

inline constexpr double kMaxAngleInput = M_PI / 2.0;  // rad: 90 deg
inline constexpr double kMaxSampleInterval = 10.0;    // s
inline constexpr double kMinSampleInterval = 1e-3;    // s: 1 kHz

// Appends one finding per experiment and suspicious column (within the experiment's window).
// Experiments whose data cannot be read are passed over (the stages report them).
void AddUnitFindings(const RunConfig& config, TrajectoryCache* cache,
                     std::vector<Finding>* findings);

}  // namespace vesselid

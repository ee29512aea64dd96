// Units a run doubts: an angle output whose column is not listed in the experiment's
// `degrees:` but looks like degrees (angle_units.h) gets a unit_suspect finding naming the experiment and
// the column. Read as radians such a heading runs to nonsense while a wrapped residual stays
// below pi.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"

namespace vesselid {

// Appends one finding per experiment and suspicious column (within the experiment's window).
// Experiments whose data cannot be read are passed over (the stages report them).
void AddUnitFindings(const RunConfig& config, TrajectoryCache* cache,
                     std::vector<Finding>* findings);

}  // namespace vesselid

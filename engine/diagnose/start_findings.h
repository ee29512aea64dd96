// Findings on how held-out runs were started: a refitted start that puts a measured state
// further from its measurement than the noise allows (implausible_start).
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/run/display_units.h"
#include "engine/solve/metrics.h"

namespace vesselid {

// One implausible_start finding per held-out run of `fits` (of stage `stage`, or "final")
// whose refitted start puts a measured state beyond its report's implausible_sds noise SDs,
// naming the worst state and the run's fit from the measured start.
void AddImplausibleStartFindings(const std::vector<ExperimentFit>& fits, const std::string& stage,
                                 const DisplayUnitOf& unit_of, std::vector<Finding>* findings);

}  // namespace vesselid

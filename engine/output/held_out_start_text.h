// What a report says of how its held-out runs were started and scored (HeldOutStartReport):
// one sentence, and with refitted starts each run's figures from its measured start beside
// the refitted ones.
#pragma once

#include <string>
#include <vector>

#include "engine/solve/metrics.h"

namespace vesselid {

// "Held-out runs are predicted from their measured start; r, delta_0 are estimated on a
// burn-in of 9-11 s at each run's start, which is not scored." Empty for training fits.
std::string HeldOutStartSentence(const std::vector<ExperimentFit>& fits);

// With refitted starts, per run and output: fit % refitted and from the measured start, and
// the measured state furthest from its refitted start (in noise SDs); empty otherwise.
// Rows are indented by `indent`.
std::string HeldOutStartTable(const std::vector<ExperimentFit>& fits, const std::string& indent);

}  // namespace vesselid

// The report.html section of a run's turning circles (output/turning_report.h).
#pragma once

#include <string>
#include <vector>

#include "engine/run/run_result.h"

namespace vesselid {

// Empty without turning circles.
std::string TurningRunsHtml(const std::vector<TurningRun>& runs);

}  // namespace vesselid

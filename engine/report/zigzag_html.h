// The zigzag figures of a run (output/zigzag_report.h) as report.html shows them.
#pragma once

#include <string>
#include <vector>

#include "engine/run/run_result.h"

namespace vesselid {

// A report.html section with its table; empty without zigzags.
std::string ZigzagRunsHtml(const std::vector<ZigzagRun>& runs);

}  // namespace vesselid

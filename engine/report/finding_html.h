// Findings (output/finding_report.h) as report.html lists them.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"

namespace vesselid {

// An HTML list per severity, each finding with its kind as a tag.
std::string FindingsHtml(const std::vector<Finding>& findings);

}  // namespace vesselid

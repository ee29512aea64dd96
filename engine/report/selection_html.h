// The report.html section of a structure selection (output/selection_report.h).
#pragma once

#include <string>

#include "engine/run/selection_result.h"

namespace vesselid {

// Empty for an empty selection.
std::string SelectionHtml(const SelectionResult& selection);

}  // namespace vesselid

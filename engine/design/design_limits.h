// The check every plan passes before it is written: each input within [lower, upper] and its
// rate, the record as long as asked, and (with a box) the predicted track inside the box.
// Violations are sentences in the units of the config (degrees where the input is given in
// degrees); none is expected, since the actuators (planned_record.h) enforce the limits.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/design/design_options.h"
#include "engine/design/input_commands.h"
#include "engine/design/planned_record.h"

namespace vesselid {

std::vector<std::string> CheckLimits(
    const DesignOptions& options, const DesignLayout& layout, const Actuators& actuators,
    const PlannedRecord& record, const std::vector<std::pair<int, std::pair<double, double>>>& box,
    const std::vector<std::string>& outputs, double sample_time);

}  // namespace vesselid

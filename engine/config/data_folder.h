// Data files stay in the data folder (--data, else the config's folder) unless the config
// allows otherwise (limits.outside_data): a config from elsewhere, or a `files: "../../*"`,
// does not read the machine's other files.
#pragma once

#include <string>

#include "engine/base/work_limits.h"

namespace vesselid {

// Empty when `file` (as the config writes it: relative to `folder` unless absolute) lies in
// `folder` or the limits allow files outside it; else why it is refused, naming the key
// that allows it.
std::string OutsideDataFolder(const std::string& file, const std::string& folder,
                              const WorkLimits& limits);

}  // namespace vesselid

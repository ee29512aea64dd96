// Data files stay in the data folder (--data, else the config's folder) unless the config
// allows otherwise (limits.outside_data): a config from elsewhere, or a `files: "../../*"`,
// does not read the machine's other files; when allowed, each file read from outside is a
// finding (outside_data_folder), so the report says where the data came from.
#pragma once

#include <string>

#include "engine/base/work_limits.h"

namespace vesselid {

// Empty when `file` (as the config writes it: relative to `folder` unless absolute) lies in
// `folder`, by its name and, with links resolved, by what it is; else the data folder
// (absolute) it lies outside of.
std::string DataFolderLeft(const std::string& file, const std::string& folder);

// Empty when `file` lies in `folder` or the limits allow files outside it; else why it is
// refused, naming the key that allows it.
std::string OutsideDataFolder(const std::string& file, const std::string& folder,
                              const WorkLimits& limits);

}  // namespace vesselid

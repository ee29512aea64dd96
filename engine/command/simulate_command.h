// `vesselid simulate` as one call, for the command line and Python alike: the config's
// synthetic experiments (its simulation section, checked whole before --out is touched),
// staged and published as one set: the files appear together, or the earlier ones stay.
// The set is the config's: simulating it again replaces what it wrote before; other
// configs' files in the folder stay.
#pragma once

#include <string>
#include <vector>

#include "engine/config/config.h"

namespace vesselid {

// `files` gets the written files' names (the config's experiment files, in out_dir).
bool SimulateCommand(const ConfigFile& config, const std::string& config_name,
                     const std::string& out_dir, bool config_is_file,
                     std::vector<std::string>* files, std::string* error);

}  // namespace vesselid

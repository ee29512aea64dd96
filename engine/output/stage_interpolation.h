// Per model input, how a stage's experiments interpolate it between samples (the method most
// of them use): how a tool that simulates the model (the C export, the FMU, Python's
// simulate) reads a record as the run did.
#pragma once

#include <map>
#include <string>

#include "engine/run/run_config.h"

namespace vesselid {

// input -> "zero_order_hold", "linear" or "cubic", for every model input.
std::map<std::string, std::string> StageInterpolation(const RunConfig& config,
                                                      const StageConfig& stage);

}  // namespace vesselid

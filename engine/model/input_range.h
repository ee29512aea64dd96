// Cutting an experiment to the stretches where its inputs lie inside configured ranges
// (`input_range: {tau_m: [0, 0.6]}`), e.g. the throttle range a model is valid in: each maximal
// stretch of rows with every ranged input inside becomes its own experiment "<name>#<k>",
// simulated from its own initial state. An input's value at a row is its last sample at or
// before it (multi-rate logs).
#pragma once

#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/model/experiment.h"

namespace vesselid {

// Appends the stretches of `spec` (within its window) to `pieces`; a spec without ranges is
// appended unchanged. A stretch that follows rows outside the ranges starts
// spec.input_range_skip later; stretches shorter than spec.input_range_min_duration are dropped.
bool SplitByInputRange(const ExperimentSpec& spec, const Trajectory& data,
                       std::vector<ExperimentSpec>* pieces, std::string* error);

}  // namespace vesselid

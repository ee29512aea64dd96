// Open-loop simulation of any model under given input signals, for synthetic experiments:
// RK4 with `substeps` steps per input sample interval, inputs interpolated between their
// samples, every model output recorded at every input sample time.
#pragma once

#include <string>
#include <vector>

#include "engine/data/interpolation.h"
#include "engine/data/trajectory.h"
#include "engine/model/model_handle.h"

namespace vesselid {

struct OpenLoopOptions {
  int substeps = 4;
  Interpolation interpolation = Interpolation::kZeroOrderHold;
  // Also a column per state, "x.<state>", after the outputs (the state at each sample time).
  bool record_states = false;
};

// `inputs` holds a column per model input it drives (others absent: NaN, allowed only for
// optional inputs). The result has the input columns followed by one column per output (and
// per state with options.record_states).
bool SimulateOpenLoop(const ModelHandle& model, const std::vector<double>& parameters,
                      const std::vector<double>& initial_state, const Trajectory& inputs,
                      const OpenLoopOptions& options, Trajectory* result, std::string* error);

}  // namespace vesselid

// Open-loop simulation of any model under given input signals (synthetic experiments, an
// identified model flown on a user's inputs): RK4 with `substeps` steps per input sample
// interval, or steps planned as a run plans them (step_plan.h), inputs interpolated between
// their samples, every model output recorded at every input sample time. The steps are the
// run's own arithmetic (rk4.h): on a record's sample times and the run's step and
// interpolation it gives the run's simulation.
#pragma once

#include <string>
#include <vector>

#include "engine/data/interpolation.h"
#include "engine/data/trajectory.h"
#include "engine/model/model_handle.h"

namespace vesselid {

struct OpenLoopOptions {
  // > 0: this many equal steps per sample interval; 0: steps of at most max_step (0: the
  // median sample interval), as a run integrates a record.
  int substeps = 4;
  double max_step = 0.0;
  Interpolation interpolation = Interpolation::kZeroOrderHold;
  // Per model input (empty: `interpolation` for every input).
  std::vector<Interpolation> input_interpolation;
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

// Equation-error data of one record (seed 000 §5.1): every signal brought to the sample
// times of one output (the slowest, e.g. GNSS at 5 Hz), causally, then smoothed and
// differentiated by Savitzky-Golay; states from the outputs and their rates by the model's
// guess (body velocities from position and heading rates), their derivatives by a second
// Savitzky-Golay pass.
//
// Causal alignment at grid time t: an output takes its last sample at or before t,
// extrapolated linearly from the sample before it (exact at its own sample times); an input
// takes its last sample (the command held by the actuator). Angle outputs are unwrapped first
// and stay continuous.
#pragma once

#include <string>

#include "engine/data/savitzky_golay.h"
#include "engine/data/trajectory.h"
#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"
#include "engine/model/regression_form.h"

namespace vesselid {

struct RegressionDataOptions {
  std::string grid_output;  // output whose sample times are the grid; empty: the sparsest
  SavitzkyGolayOptions smoothing = {4, 2, 0};  // window and degree (derivative is set inside)
  // Grid intervals up to this many median intervals are accepted (`max_gap` of a
  // least-squares or step-regression stage); see GridStepOf for longer ones.
  double max_gap = 1.5;
};

// The one rule for a step between neighbouring samples of the grid output, used both where
// records are cut into pieces and where a piece is built (so a record, resampled or not, is
// always cut or accepted):
//   kAccepted  step <= max_gap median steps;
//   kGap       longer, and at least 2 median steps: a sample is missing (a resampled
//              record's holes are whole multiples), the record is cut there;
//   kJitter    longer than max_gap but under 2 median steps: row jitter, refused with
//              advice to raise max_gap (cutting there would shred a jittery log).
enum class GridStep { kAccepted, kGap, kJitter };
GridStep GridStepOf(double step, double median_step, double max_gap);
inline constexpr double kMissingSampleStep = 2.0;  // median steps

// Builds the record of `spec` (its window) from `data`. Errors name the experiment.
bool BuildRegressionRecord(const ExperimentSpec& spec, const Trajectory& data,
                           const ModelHandle& model, const RegressionDataOptions& options,
                           RegressionRecord* record, std::string* error);

}  // namespace vesselid

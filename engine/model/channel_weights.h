// Re-weighting an experiment's output channels in place: every sample of output c gets
//   w_i <- w_i x weight_c / channel_weight_c,
// so that per-sample factors (length normalisation, outlier down-weighting) stay, and the
// initial-state prior keeps counting as one sample of the weighted noise level:
//   prior_weight <- prior_weight x sqrt(sum_c P_c weight_c^2 / sum_c P_c channel_weight_c^2),
// P_c = count x noise level^2 of channel c (Experiment::channel_noise_power).
#pragma once

#include <vector>

#include "engine/model/experiment.h"

namespace vesselid {

// `weight` per model output; outputs the experiment does not compare, or with a weight that
// is not finite and positive, keep theirs.
void SetChannelWeights(const std::vector<double>& weight, Experiment* experiment);

}  // namespace vesselid

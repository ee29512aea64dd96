// Detection of white noise on a measured input that the run treats as exact: for each
// experiment input not listed in the experiment's `input_noise`, an input_noise finding naming the
// experiment, the input and the estimated noise SD, suggesting `input_noise: {<input>: auto}`,
// when all of these hold:
//   * the input carries white noise that matters (WhiteInputNoise, data/white_noise.h);
//   * the outputs' residuals of a stage that fitted the experiment are coloured: the variance
//     of their means over blocks of B samples is above twice sigma^2 / B (what white residuals
//     give). The input noise integrated by the model shows as such slow residuals.
#pragma once

#include <string>
#include <vector>

#include "engine/base/finding.h"
#include "engine/data/white_noise.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"

namespace vesselid {

// Noisy inputs a stage treated as exact: the finding is left to stages that did not include
// the input noise in their standard errors (input_noise_uncertainty.h, `uncertainty:
// {input_noise: off}`).
void AddInputNoiseFindings(const RunConfig& config, const RunResult& run, TrajectoryCache* cache,
                           std::vector<Finding>* findings);


// Whether a residual series is coloured (block means vary more than white noise allows).
bool ResidualsColoured(const std::vector<double>& residuals);

}  // namespace vesselid

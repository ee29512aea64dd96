// held_out_beyond_band: a held-out run of the final validation, flown from its measured start,
// whose error no adjustment of the estimates and of its start within their uncertainty
// explains (PredictionBand, prediction_band.h).
//
// The band's ratio Q / samples is about 1 when the model predicts the run as well as it fits
// its training runs. The limit, with s the largest input-noise share of the last kept stage's
// training residuals (ResidualAnalysis::input_noise_share),
//   limit = (1 - s) kBandWhiteLimit + s kBandInputNoiseLimit,
// allows the white part of the error a noise level up to 12 % (in SD) above the training
// fit's, and the part logged input noise makes (a random walk of the heading, a handful of
// degrees of freedom over a run) the 99 % point of a chi-square with 2 degrees of freedom
// over its mean (9.21 / 2).
#pragma once

#include <vector>

#include "engine/base/finding.h"
#include "engine/run/run_result.h"

namespace vesselid {

inline constexpr double kBandWhiteLimit = 1.25;
inline constexpr double kBandInputNoiseLimit = 4.6;

// The limit for `run`'s final validation (above).
double PredictionBandLimit(const RunResult& run);

void AddPredictionBandFindings(const RunResult& run, std::vector<Finding>* findings);

}  // namespace vesselid

// Profile likelihood of chosen parameters of one output-error stage: confidence intervals
// that do not rest on linearising the model at the optimum.
//
// The stage is solved once (as configured) for the optimum theta^, its cost F^ and the
// residual variance s^2 = 2 F^ / (m - n). For each profiled parameter theta_j a grid of
// `points` values spans theta^_j +- span se_j (the bounds where se_j is unknown), clipped to
// the bounds; at each grid value theta_j is held and every other unknown re-estimated from
// the optimum, giving F_j(theta_j). With Gaussian noise
//   D_j(theta_j) = 2 (F_j(theta_j) - F^) / s^2  ~  chi2_1,
// so the interval is {theta_j : D_j <= chi2_1(confidence)} (3.84 for 95 %), its ends found by
// linear interpolation between grid points; an end beyond the grid is reported open. The
// linearised interval theta^_j +- z se_j is given beside it: where the two differ the
// standard errors are not to be trusted.
#pragma once

#include <string>

#include "engine/run/run_config.h"
#include "engine/study/study_options.h"
#include "engine/study/study_runner.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// On rank 0 `result` holds {confidence, threshold, stages: [{stage, optimum, profiles:
// [{parameter, estimate, lower, upper, linearised, points}], cases}]}; other ranks: null.
bool RunProfileLikelihood(const RunConfig& config, const ProfileOptions& options,
                          const CaseOptions& execution, nlohmann::json* result,
                          std::string* error, const CaseProgress& progress = nullptr);

std::string ProfileText(const nlohmann::json& result);

}  // namespace vesselid

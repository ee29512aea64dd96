// What a record's mapped columns say about the logger, as findings naming the experiment and
// the channel (in the column's unit):
//   all_zero_input        a mapped input that is exactly 0 in every sample of the window;
//   quantised             a mapped channel whose distinct values lie on a grid of step q
//                         (at least 95 % of the gaps between neighbouring distinct values are
//                         whole multiples of q, and the channel takes fewer distinct values
//                         than a fifth of its samples): a compass in whole degrees, a rudder
//                         indicator in 1-degree steps;
//   starts_mid_manoeuvre  an angle input (a rudder) whose first sample is at least 40 % of its
//                         largest magnitude: the record starts in the middle of a manoeuvre
//                         (throttles, which cruise at any value, are not judged);
//   stale_repeats         a measured output (not quantised) holding its value in runs of 3 or
//                         more equal samples (not 0) while another mapped column changes, in
//                         at least 1 % of its samples;
//   gaps                  a measured output with steps longer than 3 median sample intervals.
// Records that cannot be read are passed over (the stages report them).
#pragma once

#include <vector>

#include "engine/base/finding.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"

namespace vesselid {

void AddRecordCheckFindings(const RunConfig& config, TrajectoryCache* cache,
                            std::vector<Finding>* findings);

// The grid step of `values` when they are quantised as above, else 0.
double QuantisationStep(const std::vector<double>& values);

}  // namespace vesselid

// Multistart global start: Halton points spread over the search box (search_box.h: log
// coordinates for scale parameters, exchangeable pairs ordered) each start a short Ceres
// solve of a few iterations; a solve whose cost stays far above the best end cost of the
// earlier batches is abandoned; the end points are clustered (max-norm distance in the
// box's coordinates) and the best point of each of the best clusters becomes a candidate
// the stage refines fully.
//
// Points run in batches of kMultistartBatch in parallel; a batch sees only the best cost of
// the batches before it, so the result does not depend on the number of threads.
#pragma once

#include "engine/solve/global_start.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

constexpr int kMultistartBatch = 8;
// A short solve is abandoned once, after its first iteration, its cost exceeds this
// multiple of the best end cost of the earlier batches.
constexpr double kMultistartAbandonFactor = 10.0;

// GlobalStartOptions: points, short_iterations, candidates, min_separation, seed, threads,
// max_time_seconds. Restores the problem's values before returning.
bool RunMultistart(const GlobalStartOptions& options, OutputErrorProblem* problem,
                   GlobalStartSummary* summary);

}  // namespace vesselid

// Multistart global start: Halton points spread over the search box (search_box.h: log
// coordinates for scale parameters, exchangeable pairs ordered) are first screened by their
// cost alone (one simulation each, no Jacobian; a diverging one is dropped at the price of
// its partial simulation); the best ShortSolveCount of them, lowest cost first, each start a
// short Ceres solve of a few iterations; a solve whose cost after its first iteration is far
// above the best end cost of the earlier batches (or of an optimum the stage already holds)
// is abandoned; the end points are clustered (max-norm distance in the box's coordinates)
// and the best point of each of the best clusters becomes a candidate the stage refines
// fully, unless a known optimum lies within its cluster distance at no higher cost.
//
// Screening and short solves run in parallel; short solves in batches of kMultistartBatch,
// a batch seeing only the best cost of the batches before it, so the result does not depend
// on the number of threads.
#pragma once

#include "engine/solve/global_start.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

constexpr int kMultistartBatch = 4;
// A short solve is abandoned once, after its first iteration, its cost exceeds this
// multiple of the best end cost of the earlier batches.
constexpr double kMultistartAbandonFactor = 10.0;

// Short solves started from `finite` screened points (of a search of `dimension`
// coordinates): twice the dimension, at least twice the candidates, at most all of them.
int ShortSolveCount(int finite, int dimension, int candidates);

// GlobalStartOptions: points, short_iterations, candidates, min_separation, seed, threads,
// max_time_seconds. Restores the problem's values before returning.
bool RunMultistart(const GlobalStartOptions& options, OutputErrorProblem* problem,
                   GlobalStartSummary* summary);

}  // namespace vesselid

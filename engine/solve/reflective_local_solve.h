// The reflective trust region (reflective_trust_region.h) on an output-error problem, run
// with a Ceres solve's options and callbacks and reported as a Ceres summary, so that
// RunLocalSolve treats both alike.
#pragma once

#include "ceres/ceres.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

// Uses of `options`: max_num_iterations (trial points), the three tolerances,
// max_solver_time_in_seconds, num_threads (the experiments evaluated in parallel) and
// callbacks (after each trial point, with the problem's values at the current iterate). The
// unknowns are the problem's free, non-constant blocks, within their Ceres bounds; the
// solution is left in them.
void SolveReflectiveProblem(const ceres::Solver::Options& options, OutputErrorProblem* problem,
                            ceres::Solver::Summary* summary);

}  // namespace vesselid

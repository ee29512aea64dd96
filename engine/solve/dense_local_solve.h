// The engine's dense trust regions (dense_trust_region.h: the reflective region and
// Levenberg-Marquardt on the normal equations) on an output-error problem, run with a Ceres
// solve's options and callbacks and reported as a Ceres summary, so that RunLocalSolve treats
// them and Ceres' own minimiser alike.
#pragma once

#include "ceres/ceres.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

enum class DenseMethod { kReflective, kLevenbergMarquardt };

// Whether the problem's normal equations can be formed straight from its cost functions
// (normal_equations.h): scalar unknowns and no Ceres loss function (the engine's problems keep
// their losses inside the experiments' residuals).
bool CanSolveOnNormalEquations(OutputErrorProblem* problem);

// Uses of `options`: max_num_iterations (trial points), the three tolerances,
// max_solver_time_in_seconds, initial_trust_region_radius (Levenberg-Marquardt), num_threads
// (the experiments evaluated in parallel) and callbacks (after each trial point, with the
// problem's values at the current iterate). The unknowns are the problem's free, non-constant
// blocks, within their Ceres bounds; the solution is left in them.
void SolveOnNormalEquations(DenseMethod method, const ceres::Solver::Options& options,
                            OutputErrorProblem* problem, ceres::Solver::Summary* summary);

}  // namespace vesselid

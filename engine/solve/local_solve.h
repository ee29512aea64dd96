// Local refinement of an output-error problem: the engine's dense trust regions or Ceres' solver.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ceres/ceres.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/progress.h"

namespace vesselid {

// The local solve's method: Levenberg-Marquardt (the default: on the dense problems the
// engine's own on the normal equations, levenberg_marquardt.h, else Ceres'), Ceres' dogleg
// (bounds by projection), or the reflective trust region (reflective_trust_region.h: strictly
// interior iterates, Coleman-Li scaling, reflection off the bounds) on the normal equations
// (normal_equations.h; dense: for problems of up to some 60 unknowns). From the 3-DOF
// benchmark's far starts both engine regions reach the optimum from 10-11 of 11 starts; the
// reflective one also falls on the patrol's T1 = T2 ridge from starts on bounds and crawls
// from a tanker's far start (docs/configs.md "The local solve").
enum class TrustRegion { kLevenbergMarquardt, kDogleg, kReflective };
const char* TrustRegionToString(TrustRegion method);
bool StringToTrustRegion(const std::string& text, TrustRegion* method);

// Ceres' initial radius, nearly Gauss-Newton first steps: for the solves that start at or
// near an optimum (noise re-solves, replicates and refits, continuation phases after the
// first, held-out burn-ins, a multistart's short descents), whose first steps are the
// Gauss-Newton moves they are for.
inline constexpr double kNearOptimumRadius = 1e4;
inline constexpr double kFarStartRadius = 1.0;

struct LocalSolveOptions {
  TrustRegion trust_region = TrustRegion::kLevenbergMarquardt;
  // Linear solver; unset: AutomaticLinearSolver below.
  std::optional<ceres::LinearSolverType> linear_solver;
  int max_iterations = 200;
  // The trust region's initial radius (Levenberg-Marquardt damps its first step by
  // 1/radius, relative to the scaled normal matrix's diagonal). Unset: kFarStartRadius on
  // Levenberg-Marquardt on the normal equations (a configured start may be far: the first
  // steps are damped by half, and the radius triples after each good step; the 3-DOF far
  // starts: 11 of 11 where 1e4 reaches 10 and 8 of 11, docs/benchmarks.md), Ceres' 1e4 on
  // Ceres' minimiser (sparse problems, a named linear solver, dogleg). Solves that start at
  // or near an optimum set kNearOptimumRadius.
  std::optional<double> initial_radius;
  double function_tolerance = 1e-12;
  double gradient_tolerance = 1e-14;
  double parameter_tolerance = 1e-12;
  double max_time_seconds = 3600.0;
  // Experiments evaluated in parallel; 0: the machine's cores (one inside a parallel worker,
  // base/parallel_for.h).
  int num_threads = 0;
  ProgressCallback progress;  // after each iteration; may be empty
  // After each iteration (iteration, cost); false abandons the solve (termination
  // USER_FAILURE, not usable); the problem's values are the iteration's when it is called.
  // A multistart's short solves use it. May be empty.
  std::function<bool(int, double)> keep_going;
  // Stops, successfully (termination USER_SUCCESS), when the best cost of the last
  // `stall_window` iterations is less than a fraction `stall_tolerance` below the best before
  // them: a crawl along a valley that the relative change of one step (function_tolerance)
  // does not end. 0: off.
  int stall_window = 0;
  double stall_tolerance = 0.0;
  // A solve that ends with free unknowns on a bound goes on, within what is left of
  // max_iterations and max_time_seconds, with them held there, and keeps that when it lowers
  // the cost (local_solve.cc). Off for the short solves of searches and continuations.
  bool hold_bounds_at_end = true;

  bool IsValid(std::string* error) const;
};

// The termination of a solve that Ceres ended with FAILURE at a step whose derivatives could
// not be evaluated, resumed at its last iterate (usable, with the reason in `message`).
inline constexpr const char* kStoppedAtFailedStep = "STOPPED_AT_FAILED_STEP";

struct LocalSolveSummary {
  bool run = false;
  bool usable = false;  // Ceres ended with a usable solution
  double initial_cost = -1.0;
  double final_cost = -1.0;
  int iterations = 0;
  int successful_steps = 0;
  int unsuccessful_steps = 0;
  double time_seconds = 0.0;
  std::string termination;  // Ceres termination type
  std::string message;
  std::vector<double> cost_history;  // cost at each iteration, [0] the initial cost
  // Where the solve's time went (Ceres' own accounting): residual-only and residual+Jacobian
  // evaluations (the simulations) and the linear solver; the rest is Ceres' bookkeeping.
  double residual_seconds = 0.0, jacobian_seconds = 0.0, linear_solver_seconds = 0.0;
  int residual_evaluations = 0, jacobian_evaluations = 0;

  std::string BriefReport() const;
};

// dense_normal_cholesky while the problem is small or has no per-experiment unknowns (a
// record gives m >> n residuals: forming J'J costs m n^2 flops against 2 m n^2 for a QR of
// J, and with Jacobi scaling and the damping the factored matrix stays well conditioned;
// the MMG campaign's iteration, m = 2e4, n = 50: 23 against 35 ms); otherwise
// sparse_normal_cholesky (SuiteSparse): per-experiment initial states and parameters make
// J^T J an arrow matrix (a dense corner of shared parameters, a block diagonal of the
// rest), which a sparse Cholesky factors in time linear in the number of experiments. Schur
// elimination does not help here: every unknown is its own size-1 block, so the blocks of
// one experiment share a residual block and cannot be eliminated together.
ceres::LinearSolverType AutomaticLinearSolver(const OutputErrorProblem& problem);

// Solves from the problem's current values; leaves the solution in them.
bool RunLocalSolve(const LocalSolveOptions& options, OutputErrorProblem* problem,
                   LocalSolveSummary* summary);

}  // namespace vesselid

// Local refinement of an output-error problem with Ceres' trust-region solver.
#pragma once

#include <string>

#include "ceres/ceres.h"
#include "engine/output_error_problem.h"

namespace vesselid {

struct LocalSolveOptions {
  // Trust-region strategy: levenberg_marquardt or dogleg.
  ceres::TrustRegionStrategyType trust_region = ceres::LEVENBERG_MARQUARDT;
  // Linear solver: dense_qr for one experiment; sparse_schur / sparse_normal_cholesky
  // (SuiteSparse) when many experiments carry their own blocks.
  ceres::LinearSolverType linear_solver = ceres::DENSE_QR;
  int max_iterations = 200;
  double function_tolerance = 1e-12;
  double gradient_tolerance = 1e-14;
  double parameter_tolerance = 1e-12;
  double max_time_seconds = 3600.0;
  int num_threads = 1;  // experiments evaluated in parallel

  bool IsValid(std::string* error) const;
};

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

  std::string BriefReport() const;
};

// Solves from the problem's current values; leaves the solution in them.
bool RunLocalSolve(const LocalSolveOptions& options, OutputErrorProblem* problem,
                   LocalSolveSummary* summary);

}  // namespace vesselid

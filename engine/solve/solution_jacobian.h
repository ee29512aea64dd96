// The residuals and Jacobian of a problem at its current values (the optimum), evaluated once
// and shared by the analyses that need them (HAC covariance, local analysis), so that the
// stage simulates the experiments on Jets once after the solve rather than once per analysis.
#pragma once

#include <vector>

#include "ceres/crs_matrix.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

struct SolutionJacobian {
  std::vector<int> variables;  // free variable indices, in column order
  // Rows [0, data_rows): the experiments' samples, experiment by experiment; then every other
  // residual block (initial-state and input-correction priors), one row each.
  int data_rows = 0;
  std::vector<double> residuals;
  ceres::CRSMatrix jacobian;  // d r / d theta, theta = value / scale

  // 1/2 sum r^2 over the data rows.
  double DataCost() const;
};

// False when a simulation diverges at the current values.
bool EvaluateSolutionJacobian(OutputErrorProblem* problem, int num_threads, SolutionJacobian* out);

}  // namespace vesselid

// Local analysis of an output-error problem at its optimum: how well the data determine the
// shared model parameters, and how strongly each output channel responds to each of them.
//
// J is the Jacobian of the (weighted) residuals with respect to the free variables in
// physical units (dr/dp = dr/dtheta / scale). With p the shared free parameters and s the
// per-experiment unknowns (free initial states, per-experiment parameters), J^T J is an arrow
// matrix whose s-part is block diagonal by experiment; profiling s out gives the information
// of p alone, accumulated experiment by experiment (no dense m x n Jacobian is formed):
//   I = I_pp - sum_e I_ps,e I_ss,e^+ I_sp,e           (Schur complement, ^+ pseudo-inverse)
// In column-normalised coordinates, N = D^-1 I D^-1 with D = sqrt(diag(I_pp)) (the norms of
// the Jacobian columns, so a parameter the states absorb completely shows as a zero
// eigenvalue):
//   N v_k = lambda_k v_k,   condition number = sqrt(lambda_max / lambda_min)  (inf if <= 0)
// and with s^2 = 2 F / (m - n) (as covariance.h), Cov(p) = s^2 D^-1 N^+ D^-1, so the standard
// errors agree with ComputeUncertainty's for the shared parameters.
//
// A direction v_k is reported as the parameter change dp = t D^-1 v_k written as a
// combination ("T2 + 0.97 T3": dT2 = t, dT3 = 0.97 t), terms by decreasing normalised
// component, led by the largest (coefficient 1); other terms whose normalised component is
// below `min_component` are dropped. Its standard deviation is that of t, in the leading
// parameter's units: std(t) = |(D^-1 v_k)_lead| s / sqrt(lambda_k); s / sqrt(lambda_k) itself
// is kept too. Status by lambda_k / lambda_max (default thresholds): below 1e-10 (singular
// values 1e-5 of the largest) undetermined, the data practically do not constrain the
// change; below 1e-4 (a condition number above 100 along it) poorly determined; else
// determined.
//
// Sensitivity of output channel c to shared parameter p_j, over every sample i of the channel
// in all experiments (y_ci measured; dy/dp = (dr/dp) / w_i, the simulated output's):
//   S_cj = |p_j| RMS_i(dy_ci/dp_j) / RMS_i(y_ci - mean_e y_c)        ("% per %")
//   Z_cj = |p_j| RMS_i(dr_ci/dp_j) / s                               (in noise units)
// The channel's size is its RMS about its mean in each experiment (angles taken relative to
// the experiment's first sample), so that the arbitrary origin of a position or heading does
// not dilute it. |p_j| is replaced by 1 where p_j = 0 (then per unit change, not per %).
// With a robust loss the Jacobian is that of the robust residuals (as in covariance.h).
#pragma once

#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/solution_jacobian.h"

namespace vesselid {

enum class DirectionStatus { kUndetermined, kPoorlyDetermined, kDetermined };
const char* DirectionStatusToString(DirectionStatus status);  // "undetermined", ...

struct LocalAnalysisOptions {
  int num_threads = 1;                // Jacobian evaluation
  double poor_ratio = 1e-4;           // lambda / lambda_max below: poorly determined
  double undetermined_ratio = 1e-10;  // lambda / lambda_max below: undetermined
  double min_component = 0.05;        // normalised components below are not named
};

// One eigen-direction of the normalised information matrix.
struct WeakDirection {
  std::string combination;           // "T2 + 0.97 T3"
  std::vector<double> coefficients;  // dp / t per parameter (leading 1; dropped terms 0)
  double eigenvalue_ratio = 0.0;     // lambda / lambda_max
  double std_dev = 0.0;              // of t, in the leading parameter's units
  double std_dev_normalised = 0.0;   // s / sqrt(lambda)
  DirectionStatus status = DirectionStatus::kDetermined;
};

struct LocalAnalysis {
  bool available = false;
  std::string message;             // why not available
  std::vector<int> parameters;     // shared free variable indices, matrix order
  std::vector<std::string> names;  // their names
  int profiled = 0;                // per-experiment unknowns profiled out
  int num_residuals = 0;
  int num_free = 0;
  double residual_variance = 0.0;  // s^2
  Eigen::MatrixXd information;     // I, physical units (without 1 / s^2)
  Eigen::VectorXd eigenvalues;     // of N, ascending
  double condition_number = 0.0;   // inf when lambda_min <= 0
  // Every direction below poor_ratio and always the weakest one, weakest first.
  std::vector<WeakDirection> directions;
  std::vector<double> std_errors;     // from s^2 I^+ (NaN where undetermined)
  std::vector<std::string> channels;  // model outputs compared
  Eigen::MatrixXd sensitivity;        // S, channels x parameters
  Eigen::MatrixXd noise_sensitivity;  // Z, channels x parameters
  double time_seconds = 0.0;
};

// Analyses the problem at its current values (the optimum). False, with analysis->message,
// when there is nothing to analyse or the Jacobian cannot be evaluated. `shared` (may be
// null): the residuals and Jacobian already evaluated there (EvaluateSolutionJacobian).
bool ComputeLocalAnalysis(const LocalAnalysisOptions& options, OutputErrorProblem* problem,
                          LocalAnalysis* analysis, const SolutionJacobian* shared = nullptr);

}  // namespace vesselid

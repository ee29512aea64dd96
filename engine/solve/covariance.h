// Parameter uncertainty at the optimum (the Hessian, or Gauss-Newton, covariance):
//   Cov(theta) = s^2 (J^T J)^-1,  s^2 = 2 F / (m - n)   (F final cost, m residuals, n free)
// converted to physical units with the scales, plus standard errors and correlations. J is
// every residual block's Jacobian (data and priors); (J^T J)^-1 comes from the SVD of the
// column-normalised triangular factor R of J (arrow_qr.h), n x n, so memory stays that of
// the Jacobian however many samples there are.
// A rank-deficient Jacobian is reported, with the combinations that are undetermined; the
// covariance is then the pseudo-inverse over the determined subspace.
// When the dense n x n matrices exceed the memory budget, or n exceeds 1 000 with free
// initial states or per-experiment values among them, R is kept by blocks (ArrowQrBlocks) and the
// covariance is the shared variables' alone, (R_pp^T R_pp)^-1 (the inverse of the Schur complement:
// exact), with each per-experiment variable's standard error from its rows of R^-1:
//   Cov_gg = R_gg^-1 R_gg^-T + B C_pp B^T,  B = R_gg^-1 R_gp.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/solution_jacobian.h"

namespace vesselid {

struct Uncertainty {
  bool available = false;
  std::string message;         // why not available, or a rank-deficiency note
  std::vector<int> variables;  // free variable indices, in matrix order
  Eigen::MatrixXd covariance;  // physical units
  Eigen::MatrixXd correlation;
  std::vector<double> std_errors;  // sqrt of the diagonal
  double residual_variance = 0.0;  // s^2
  // Directions the data do not determine (rank deficiency), each as the unit direction in
  // physical units along which the fit does not change ("+0.71 Iz +0.71 Nrdot"), and the
  // variables taking part in any of them. Their
  // standard errors are NaN; the others come from the pseudo-inverse, which is exact for
  // the determined subspace.
  std::vector<std::string> undetermined;
  std::vector<int> undetermined_variables;
  // How the covariance was estimated: "hessian" (above) or another UncertaintyMethod
  // (uncertainty_method.h); when another, the Hessian's standard errors beside it, and why.
  std::string method = "hessian";
  std::vector<double> hessian_std_errors;  // empty when method is "hessian"
  std::string method_reason;
  double hac_bandwidth = 0.0;  // sandwich_hac: largest kernel bandwidth S, in time nodes
  // Bootstrap methods: replicates run and failed; block_bootstrap: the longest block, s.
  int bootstrap_runs = 0, bootstrap_failed = 0;
  double block_length = 0.0;
  // Bootstrap methods: each solved replicate's values of `variables` (physical units) and
  // the variables' names ("T1", "delta_0[run2]"): the ensemble an exported model carries.
  std::vector<std::vector<double>> replicates;
  std::vector<std::string> replicate_names;
  // Noise on measured inputs held exact (engine/run/input_noise_uncertainty.h): the refits
  // run and failed, the inputs ("<experiment>:<input>"), the input noise's part of each
  // standard error (order of `variables`; already in std_errors), and per experiment and
  // output the largest share of the residual power the input noise can make (99 % quantile).
  int input_noise_runs = 0, input_noise_failed = 0;
  std::vector<std::string> input_noise_inputs;
  std::vector<double> input_noise_std_errors;
  std::map<std::string, std::map<std::string, double>> input_noise_share;

  // Per-experiment variables whose standard errors come without their covariances (the
  // block-structured case above); `variables` then holds the shared variables only.
  std::vector<int> block_variables;
  std::vector<double> block_std_errors;

  // Standard error of variable `index`, or NaN if unknown.
  double StdError(int index) const;
};

// std_errors (NaN for undetermined_variables) and correlation from covariance, within
// [-1, 1].
void SetStdErrorsAndCorrelation(Uncertainty* uncertainty);

// `solution` (may be null): the Jacobian already evaluated at the current values
// (EvaluateSolutionJacobian); otherwise it is evaluated here on one thread.
bool ComputeUncertainty(OutputErrorProblem* problem, double final_cost, Uncertainty* uncertainty,
                        const SolutionJacobian* solution = nullptr);

}  // namespace vesselid

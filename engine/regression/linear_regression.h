// Equation-error (linear-in-the-parameters) least squares, y = X theta + e, as the start of an
// output-error refinement (seed 000's procedure, seed 003's robust weighting):
//
//   min over theta  sum_i w_i (y_i - x_i theta)^2 + penalty(theta)
//
//   penalty: none | ridge lambda |theta~|^2 | lasso lambda |theta~|_1, on the standardised
//            columns (theta~ = theta * column RMS), so lambda does not depend on units; a
//            negative lambda is chosen by k-fold cross-validation over a log grid.
//   robust:  seed 003: samples with |e_i - median(e)| > 3 S_MAD (S_MAD = 1.4826 MAD) are
//            rejected after the first fit; the rest get adaptive weights
//            w_i = 2 / (1 + exp(|e_i| / T')), T' the mean of the medians of the second and
//            third quarters of the sorted |e|; the fit is repeated with them.
//
// Covariance: s^2 (X^T W X)^-1 without a penalty; with ridge the sandwich
// s^2 H^-1 X^T W X H^-1, H = X^T W X + lambda D^2; none for lasso (NaN standard errors).
#pragma once

#include <string>
#include <vector>

#include "Eigen/Dense"

namespace vesselid {

enum class Penalty { kNone, kRidge, kLasso };

struct RegressionOptions {
  Penalty penalty = Penalty::kNone;
  double lambda = -1.0;  // < 0: cross-validated (with a penalty)
  int folds = 5;         // contiguous blocks: neighbouring samples are correlated
  bool robust = false;
  int robust_iterations = 3;  // weight updates after the rejection
};

struct RegressionResult {
  Eigen::VectorXd theta;
  Eigen::VectorXd std_errors;  // NaN where unknown (lasso)
  Eigen::MatrixXd covariance;
  double lambda = 0.0;
  int rejected = 0;             // samples the 3 S_MAD rule removed
  Eigen::VectorXd weights;      // final sample weights (0: rejected)
  double residual_rms = 0.0;    // weighted RMS residual of the kept samples
  double r2 = 0.0;              // of the kept samples, unweighted
};

// False with a message if X and y do not fit or the problem has fewer samples than columns.
bool SolveRegression(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                     const RegressionOptions& options, RegressionResult* result,
                     std::string* error);

}  // namespace vesselid

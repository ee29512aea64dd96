// Weighted lasso with a regularisation path and leave-one-group-out cross-validation (seed 004,
// Eriksen & Breivik, eqs. (9)-(11) and "Cross-Validation"):
//
//   eps(beta) = (1/N) sum_i W_ii (y_i - phi_i' beta)^2 + lambda sum_j f_j |beta_j|
//
// f_j are per-coefficient penalty factors (0: unpenalised, e.g. an intercept). Dropping the
// constant y'Wy / N, eps is the quadratic form 1/2 b'Gb - m'b + sum_j lambda f_j |b_j| with
// G = (2/N) X'WX and m = (2/N) X'Wy, which SolveLassoGram minimises by coordinate descent.
//
// The path runs from lambda_max, the smallest lambda at which every penalised coefficient is
// zero, down to path_ratio * lambda_max. With U the unpenalised columns and b_U their fit alone
// (G_UU b_U = m_U), the gradient at (b_U, 0) is zero on U and -(m_j - G_jU b_U) elsewhere, so
//
//   lambda_max = max over penalised j of |m_j - G_jU b_U| / f_j.
//
// Cross-validation leaves out one group of samples at a time (steady-state points from repeated
// or mirrored steps share a group, so near-duplicates never sit on both sides). The fold's
// X'WX and X'Wy are the full ones minus the left-out group's, the fold's N is N minus the
// group's size, and each fold runs the full path's lambdas from the top with warm starts.
#pragma once

#include <string>
#include <vector>

#include "Eigen/Dense"

namespace vesselid {

// Minimises 1/2 b'Gb - m'b + sum_j penalty_j |b_j| (G symmetric positive semi-definite,
// penalty_j >= 0) by cyclic coordinate descent, warm-started from *beta (in/out; resized to
// zeros if its size does not match). Whenever a sweep leaves the signs unchanged, a feature-sign
// step solves for the stationary point of that sign pattern and moves there (or towards it,
// up to the first coefficient that reaches zero); a point satisfying the optimality conditions
// ends the descent, so solutions are exact even on strongly correlated columns. Coefficients of
// columns with G_jj <= 0 are set to zero. Returns the sweeps used; `tolerance` bounds the last
// sweep's largest change sqrt(G_jj) |delta b_j| relative to the largest sqrt(G_jj) |b_j|.
int SolveLassoGram(const Eigen::MatrixXd& gram, const Eigen::VectorXd& moment,
                   const Eigen::VectorXd& penalty, Eigen::VectorXd* beta, int max_sweeps = 10000,
                   double tolerance = 1e-12);

struct LassoOptions {
  Eigen::VectorXd penalty_factors;  // f_j >= 0, one per column; empty: all 1
  int path_points = 50;             // lambdas, log-spaced from lambda_max down
  double path_ratio = 1e-4;         // lambda_min / lambda_max, in (0, 1]
  int max_sweeps = 10000;           // coordinate-descent sweeps per lambda
  double tolerance = 1e-12;         // see SolveLassoGram

  // At least one penalised column (f_j > 0) is required.
  bool IsValid(int columns, std::string* error) const;
};

struct LassoPath {
  std::vector<double> lambda;             // decreasing; lambda[0] = lambda_max (all penalised 0)
  Eigen::MatrixXd beta;                   // path_points x columns, fit on all samples
  std::vector<int> nonzero;               // nonzero coefficients per lambda (unpenalised too)
  std::vector<double> cv_error;           // leave-one-group-out sum W e^2 / sum W
  std::vector<double> cv_standard_error;  // its SE over groups (see below)
  int best = -1;                          // index of the minimum cv_error (first, if tied)
  int one_standard_error = -1;            // sparsest index with cv_error <= min + its SE
  int groups = 0;
  int sweeps = 0;  // coordinate-descent sweeps over the whole path and all folds
};

// Fits the whole path on all samples and cross-validates it leaving out one group at a time.
// x: N x p, y: N, w: N weights > 0, group: N ids (any ints). The CV error at each lambda is the
// W-weighted mean squared prediction error over all left-out samples; with e_g the weighted
// mean of group g and W_g its weight sum, the standard error is
// sqrt(sum_g W_g (e_g - cv)^2 / sum_g W_g / (groups - 1)). False with a message on bad input
// (sizes, non-finite values, fewer than 2 groups, non-positive weights, invalid options).
bool CrossValidateLasso(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                        const Eigen::VectorXd& w, const std::vector<int>& group,
                        const LassoOptions& options, LassoPath* path, std::string* error);

// The fit at one lambda on all samples, from `start` if given (and of the right size), else
// from the unpenalised columns' fit alone. Weights >= 0 (0 drops a sample). Inputs must be
// valid (consistent sizes, finite, valid options): violations are internal errors.
Eigen::VectorXd FitLasso(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                         const Eigen::VectorXd& w, double lambda, const LassoOptions& options,
                         const Eigen::VectorXd* start = nullptr);

// lambda_max of the quadratic form above for penalty factors f (see the header comment), and
// the fit of the unpenalised columns alone (zero elsewhere) in *unpenalised_fit.
double LassoLambdaMax(const Eigen::MatrixXd& gram, const Eigen::VectorXd& moment,
                      const Eigen::VectorXd& factors, Eigen::VectorXd* unpenalised_fit);

}  // namespace vesselid

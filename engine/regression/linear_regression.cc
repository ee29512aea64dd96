#include "engine/regression/linear_regression.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/base/nan.h"
#include "engine/base/statistics.h"
#include "engine/regression/lasso.h"

namespace vesselid {
namespace {

// Weighted penalised fit on columns scaled by `scale` (theta = theta~ / scale).
Eigen::VectorXd Fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const Eigen::VectorXd& w,
                    const Eigen::VectorXd& scale, Penalty penalty, double lambda) {
  const Eigen::MatrixXd xs = x * scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd gram = xs.transpose() * w.asDiagonal() * xs;
  const Eigen::VectorXd moment = xs.transpose() * w.cwiseProduct(y);
  const int p = static_cast<int>(x.cols());
  Eigen::VectorXd theta;
  if (penalty != Penalty::kLasso) {
    Eigen::MatrixXd h = gram;
    if (penalty == Penalty::kRidge) h.diagonal().array() += lambda;
    theta = h.completeOrthogonalDecomposition().solve(moment);
  } else {
    // 1/2 t'Gt - m't + lambda |t|_1, from the least-squares solution.
    theta = gram.completeOrthogonalDecomposition().solve(moment);
    SolveLassoGram(gram, moment, Eigen::VectorXd::Constant(p, lambda), &theta);
  }
  return theta.cwiseQuotient(scale);
}

// Lambda with the lowest k-fold (contiguous blocks) prediction error over a log grid.
double CrossValidate(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const Eigen::VectorXd& w,
                     const Eigen::VectorXd& scale, Penalty penalty, int folds) {
  const int n = static_cast<int>(x.rows());
  const Eigen::MatrixXd xs = x * scale.cwiseInverse().asDiagonal();
  const double top = std::max((xs.transpose() * w.cwiseProduct(y)).cwiseAbs().maxCoeff(), 1e-12);
  double best_lambda = 0.0, best_error = std::numeric_limits<double>::infinity();
  for (int g = 0; g <= 40; ++g) {
    const double lambda = top * std::pow(10.0, -8.0 + 0.2 * g);  // 1e-8 .. 1 of the top
    double error = 0.0;
    for (int f = 0; f < folds; ++f) {
      const int begin = n * f / folds, end = n * (f + 1) / folds;
      Eigen::VectorXd train = w;
      train.segment(begin, end - begin).setZero();
      const Eigen::VectorXd theta = Fit(x, y, train, scale, penalty, lambda);
      const Eigen::VectorXd r =
          y.segment(begin, end - begin) - x.middleRows(begin, end - begin) * theta;
      error += r.cwiseAbs2().dot(w.segment(begin, end - begin));
    }
    if (error < best_error) {
      best_error = error;
      best_lambda = lambda;
    }
  }
  return best_lambda;
}

}  // namespace

bool SolveRegression(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                     const RegressionOptions& options, RegressionResult* result,
                     std::string* error) {
  const int n = static_cast<int>(x.rows()), p = static_cast<int>(x.cols());
  if (y.size() != n) {
    *error = "regression: " + std::to_string(n) + " rows of regressors but " +
             std::to_string(y.size()) + " targets";
    return false;
  }
  if (n <= p || p == 0) {
    *error = "regression: " + std::to_string(n) + " samples for " + std::to_string(p) +
             " parameters";
    return false;
  }
  if (!x.allFinite() || !y.allFinite()) {
    *error = "regression: regressors or targets are not finite";
    return false;
  }
  if (options.penalty != Penalty::kNone && options.folds < 2) {
    *error = "regression: cross-validation needs at least 2 folds";
    return false;
  }
  RegressionResult r;
  Eigen::VectorXd scale = (x.cwiseAbs2().colwise().sum() / n).cwiseSqrt().transpose();
  for (int j = 0; j < p; ++j) {
    if (!(scale[j] > 0.0)) scale[j] = 1.0;
  }
  r.weights = Eigen::VectorXd::Ones(n);
  auto solve = [&]() {
    r.lambda = options.penalty == Penalty::kNone ? 0.0
               : options.lambda >= 0.0
                   ? options.lambda
                   : CrossValidate(x, y, r.weights, scale, options.penalty, options.folds);
    r.theta = Fit(x, y, r.weights, scale, options.penalty, r.lambda);
  };
  solve();
  if (options.robust) {
    Eigen::VectorXd e = y - x * r.theta;
    std::vector<double> residuals(e.data(), e.data() + n);
    const double median = Median(residuals, 0.0);
    std::vector<double> deviation(n);
    for (int i = 0; i < n; ++i) deviation[i] = std::abs(e[i] - median);
    const double s_mad = 1.4826 * Median(deviation, 0.0);
    for (int i = 0; i < n; ++i) {
      if (deviation[i] > 3.0 * s_mad) {
        r.weights[i] = 0.0;
        ++r.rejected;
      }
    }
    for (int iteration = 0; iteration < options.robust_iterations; ++iteration) {
      solve();
      e = y - x * r.theta;
      std::vector<double> kept;
      for (int i = 0; i < n; ++i) {
        if (r.weights[i] > 0.0) kept.push_back(std::abs(e[i]));
      }
      std::sort(kept.begin(), kept.end());
      const size_t m = kept.size();
      const double t1 = Median({kept.begin() + m / 4, kept.begin() + m / 2}, 0.0);
      const double t2 = Median({kept.begin() + m / 2, kept.begin() + 3 * m / 4}, 0.0);
      const double t = 0.5 * (t1 + t2);
      if (!(t > 0.0)) break;
      for (int i = 0; i < n; ++i) {
        if (r.weights[i] > 0.0) r.weights[i] = 2.0 / (1.0 + std::exp(std::abs(e[i]) / t));
      }
    }
    solve();
  }

  const Eigen::VectorXd e = y - x * r.theta;
  const double kept = static_cast<double>((r.weights.array() > 0.0).count());
  const double weighted = e.cwiseAbs2().dot(r.weights);
  const double weight_sum = r.weights.sum();
  r.residual_rms = std::sqrt(weighted / weight_sum);
  double mean = 0.0;
  for (int i = 0; i < n; ++i) mean += r.weights[i] > 0.0 ? y[i] : 0.0;
  mean /= kept;
  double total = 0.0, residual = 0.0;
  for (int i = 0; i < n; ++i) {
    if (r.weights[i] <= 0.0) continue;
    total += (y[i] - mean) * (y[i] - mean);
    residual += e[i] * e[i];
  }
  r.r2 = total > 0.0 ? 1.0 - residual / total : kNaN;

  // s^2 from the weighted residuals with the effective sample count of the weights.
  const double s2 = weighted / weight_sum * kept / std::max(kept - p, 1.0);
  const Eigen::MatrixXd gram = x.transpose() * r.weights.asDiagonal() * x * (kept / weight_sum);
  if (options.penalty == Penalty::kLasso) {
    r.covariance = Eigen::MatrixXd::Constant(p, p, kNaN);
  } else {
    // Inverted on the scaled columns (x_j / scale_j) and scaled back, so that the standard
    // errors do not depend on the regressors' units: unscaled, a column in rpm^2 next to one
    // of order 1 puts the others below the pseudo-inverse's rank threshold.
    const Eigen::VectorXd inv_scale = scale.cwiseInverse();
    Eigen::MatrixXd h = inv_scale.asDiagonal() * gram * inv_scale.asDiagonal();
    if (options.penalty == Penalty::kRidge) h.diagonal().array() += r.lambda * (kept / weight_sum);
    const Eigen::MatrixXd inverse = inv_scale.asDiagonal() *
                                    h.completeOrthogonalDecomposition().pseudoInverse() *
                                    inv_scale.asDiagonal();
    r.covariance = s2 * inverse * gram * inverse;
  }
  r.std_errors = r.covariance.diagonal().cwiseSqrt();
  *result = std::move(r);
  return true;
}

}  // namespace vesselid

#include "engine/regression/lasso.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/base/check.h"

namespace vesselid {
namespace {

// A coefficient at zero whose |rho| exceeds its penalty only by rounding stays at zero, so the
// fit at exactly lambda_max is exactly zero on the penalised columns.
constexpr double kWakeMargin = 1e-13;
// Relative slack of the optimality check of a directly solved sign pattern: far above the
// rounding of m_j - G_j z, far below any change of the fit that matters.
constexpr double kKktSlack = 1e-10;
// The maintained gradient is recomputed every so many sweeps against drift.
constexpr int kRefreshSweeps = 64;

int Sign(double v) { return (v > 0.0) - (v < 0.0); }

// 1/2 b'Gb - m'b + penalty'|b|, and in *size the sum of its terms' magnitudes (its rounding
// scale).
double Objective(const Eigen::MatrixXd& gram, const Eigen::VectorXd& moment,
                 const Eigen::VectorXd& penalty, const Eigen::VectorXd& b, double* size) {
  const double quadratic = 0.5 * b.dot(gram * b), linear = moment.dot(b);
  const double l1 = penalty.dot(b.cwiseAbs());
  *size = std::abs(quadratic) + std::abs(linear) + l1;
  return quadratic - linear + l1;
}

enum class DirectStep { kOptimal, kMoved, kFailed };

// Feature-sign step on the current sign pattern s of *beta (active set A = nonzeros): the
// objective restricted to that orthant is the quadratic minimised by z,
// G_AA z_A = m_A - penalty_A s_A, z = 0 off A. If z keeps the signs, *beta moves to z
// (optimal if the conditions also hold off A); otherwise it moves along z - beta up to the
// first penalised coefficient that reaches zero, which it zeroes. Either move lowers the
// objective (checked, so a singular G_AA cannot make things worse).
DirectStep FeatureSignStep(const Eigen::MatrixXd& gram, const Eigen::VectorXd& moment,
                           const Eigen::VectorXd& penalty, const Eigen::VectorXd& scale,
                           Eigen::VectorXd* beta) {
  const int p = static_cast<int>(moment.size());
  Eigen::VectorXd& b = *beta;
  std::vector<int> active;
  for (int j = 0; j < p; ++j) {
    if (b[j] != 0.0) active.push_back(j);
  }
  const int k = static_cast<int>(active.size());
  Eigen::VectorXd z = Eigen::VectorXd::Zero(p);
  if (k > 0) {
    Eigen::MatrixXd g(k, k);
    Eigen::VectorXd rhs(k);
    for (int a = 0; a < k; ++a) {
      for (int c = 0; c < k; ++c) g(a, c) = gram(active[a], active[c]);
      rhs[a] = moment[active[a]] - penalty[active[a]] * Sign(b[active[a]]);
    }
    // Cholesky, much faster than pivoted LDLT at this size; LDLT when G_AA is singular.
    const Eigen::LLT<Eigen::MatrixXd> cholesky(g);
    const Eigen::VectorXd solution = cholesky.info() == Eigen::Success
                                         ? Eigen::VectorXd(cholesky.solve(rhs))
                                         : Eigen::VectorXd(g.ldlt().solve(rhs));
    if (!solution.allFinite()) return DirectStep::kFailed;
    for (int a = 0; a < k; ++a) z[active[a]] = solution[a];
  }
  // Largest step t in (0, 1] along z - b that keeps every penalised sign.
  double t = 1.0;
  int crossing = -1;
  for (int j : active) {
    if (penalty[j] > 0.0 && Sign(z[j]) != Sign(b[j])) {
      const double reach = b[j] / (b[j] - z[j]);
      if (reach < t) {
        t = reach;
        crossing = j;
      }
    }
  }
  Eigen::VectorXd moved = crossing < 0 ? z : Eigen::VectorXd(b + t * (z - b));
  if (crossing >= 0) moved[crossing] = 0.0;
  double size_before, size_after;
  const double before = Objective(gram, moment, penalty, b, &size_before);
  const double after = Objective(gram, moment, penalty, moved, &size_after);
  if (!(after <= before + 1e-13 * std::max(size_before, size_after))) return DirectStep::kFailed;
  b = moved;
  if (crossing >= 0) return DirectStep::kMoved;
  const Eigen::VectorXd residual = moment - gram * z;  // minus the gradient
  const Eigen::VectorXd rounding = moment.cwiseAbs() + gram.cwiseAbs() * z.cwiseAbs();
  for (int j = 0; j < p; ++j) {
    if (scale[j] == 0.0) continue;  // a zero column: z_j = 0, no condition
    const double slack = kKktSlack * rounding[j];
    if (z[j] != 0.0) {
      if (std::abs(residual[j] - penalty[j] * Sign(z[j])) > slack) return DirectStep::kMoved;
    } else if (std::abs(residual[j]) > penalty[j] + slack) {
      return DirectStep::kMoved;
    }
  }
  return DirectStep::kOptimal;
}

Eigen::VectorXd Factors(const LassoOptions& options, int columns) {
  return options.penalty_factors.size() == 0 ? Eigen::VectorXd::Ones(columns)
                                             : options.penalty_factors;
}

std::vector<double> LambdaGrid(double lambda_max, const LassoOptions& options) {
  std::vector<double> lambda(options.path_points);
  for (int k = 0; k < options.path_points; ++k) {
    const double t = options.path_points > 1 ? double(k) / (options.path_points - 1) : 0.0;
    lambda[k] = lambda_max * std::pow(options.path_ratio, t);
  }
  return lambda;
}

}  // namespace

int SolveLassoGram(const Eigen::MatrixXd& gram, const Eigen::VectorXd& moment,
                   const Eigen::VectorXd& penalty, Eigen::VectorXd* beta, int max_sweeps,
                   double tolerance) {
  const int p = static_cast<int>(moment.size());
  VESSELID_CHECK(gram.rows() == p && gram.cols() == p && penalty.size() == p);
  VESSELID_CHECK((penalty.array() >= 0.0).all());
  Eigen::VectorXd& b = *beta;
  if (b.size() != p) b = Eigen::VectorXd::Zero(p);
  Eigen::VectorXd scale(p);  // sqrt(G_jj): the size of a coefficient's effect on the fit
  std::vector<int> pattern(p);
  for (int j = 0; j < p; ++j) {
    scale[j] = gram(j, j) > 0.0 ? std::sqrt(gram(j, j)) : 0.0;
    if (scale[j] == 0.0) b[j] = 0.0;
    pattern[j] = Sign(b[j]);
  }
  Eigen::VectorXd residual = moment - gram * b;  // minus the gradient of the smooth part
  int next_attempt = 1, backoff = 1;
  int sweep = 0;
  while (sweep < max_sweeps) {
    ++sweep;
    if (sweep % kRefreshSweeps == 0) residual = moment - gram * b;
    double change = 0.0, size = 0.0;
    bool pattern_changed = false;
    for (int j = 0; j < p; ++j) {
      if (scale[j] == 0.0) continue;
      const double rho = residual[j] + gram(j, j) * b[j];
      if (b[j] == 0.0 && std::abs(rho) <= penalty[j] * (1.0 + kWakeMargin)) continue;
      const double updated =
          std::copysign(std::max(std::abs(rho) - penalty[j], 0.0), rho) / gram(j, j);
      const double delta = updated - b[j];
      if (delta != 0.0) {
        residual.noalias() -= gram.col(j) * delta;
        b[j] = updated;
      }
      change = std::max(change, scale[j] * std::abs(delta));
      size = std::max(size, scale[j] * std::abs(updated));
      if (Sign(updated) != pattern[j]) {
        pattern[j] = Sign(updated);
        pattern_changed = true;
      }
    }
    if (change <= tolerance * size) break;
    if (pattern_changed) {
      backoff = 1;
      next_attempt = sweep + 1;
      continue;
    }
    if (sweep < next_attempt) continue;
    const DirectStep step = FeatureSignStep(gram, moment, penalty, scale, &b);
    if (step == DirectStep::kOptimal) break;
    if (step == DirectStep::kMoved) {
      residual = moment - gram * b;
      for (int j = 0; j < p; ++j) pattern[j] = Sign(b[j]);
      backoff = 1;
    } else {
      backoff *= 2;
    }
    next_attempt = sweep + backoff;
  }
  return sweep;
}

bool LassoOptions::IsValid(int columns, std::string* error) const {
  if (penalty_factors.size() != 0 && penalty_factors.size() != columns) {
    *error = "lasso: " + std::to_string(penalty_factors.size()) + " penalty factors for " +
             std::to_string(columns) + " columns";
    return false;
  }
  if (!penalty_factors.allFinite() || (penalty_factors.array() < 0.0).any()) {
    *error = "lasso: penalty factors must be finite and >= 0";
    return false;
  }
  if (penalty_factors.size() != 0 && !(penalty_factors.array() > 0.0).any()) {
    *error = "lasso: every penalty factor is 0, nothing is penalised";
    return false;
  }
  if (path_points < 1) {
    *error = "lasso: path_points must be >= 1, not " + std::to_string(path_points);
    return false;
  }
  if (!(path_ratio > 0.0 && path_ratio <= 1.0)) {
    *error = "lasso: path_ratio must be in (0, 1], not " + std::to_string(path_ratio);
    return false;
  }
  if (max_sweeps < 1 || !(tolerance >= 0.0)) {
    *error = "lasso: max_sweeps must be >= 1 and tolerance >= 0";
    return false;
  }
  return true;
}

double LassoLambdaMax(const Eigen::MatrixXd& gram, const Eigen::VectorXd& moment,
                      const Eigen::VectorXd& factors, Eigen::VectorXd* unpenalised_fit) {
  const int p = static_cast<int>(moment.size());
  VESSELID_CHECK(gram.rows() == p && gram.cols() == p && factors.size() == p);
  std::vector<int> free;
  for (int j = 0; j < p; ++j) {
    if (factors[j] == 0.0 && gram(j, j) > 0.0) free.push_back(j);
  }
  Eigen::VectorXd& fit = *unpenalised_fit;
  fit = Eigen::VectorXd::Zero(p);
  if (!free.empty()) {
    const Eigen::MatrixXd g = gram(free, free);
    const Eigen::VectorXd m = moment(free);
    const Eigen::VectorXd solution = g.completeOrthogonalDecomposition().solve(m);
    fit(free) = solution;
  }
  // The same expression as SolveLassoGram's first gradient, so the threshold matches bitwise.
  const Eigen::VectorXd residual = moment - gram * fit;
  double lambda_max = 0.0;
  for (int j = 0; j < p; ++j) {
    if (factors[j] > 0.0 && gram(j, j) > 0.0) {
      lambda_max = std::max(lambda_max, std::abs(residual[j]) / factors[j]);
    }
  }
  return lambda_max;
}

Eigen::VectorXd FitLasso(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                         const Eigen::VectorXd& w, double lambda, const LassoOptions& options,
                         const Eigen::VectorXd* start) {
  const int n = static_cast<int>(x.rows()), p = static_cast<int>(x.cols());
  std::string error;
  VESSELID_CHECK(options.IsValid(p, &error));
  VESSELID_CHECK(n > 0 && y.size() == n && w.size() == n && lambda >= 0.0);
  const Eigen::VectorXd factors = Factors(options, p);
  const Eigen::MatrixXd gram = (2.0 / n) * (x.transpose() * w.asDiagonal() * x);
  const Eigen::VectorXd moment = (2.0 / n) * (x.transpose() * w.cwiseProduct(y));
  Eigen::VectorXd beta;
  if (start != nullptr && start->size() == p) {
    beta = *start;
  } else {
    LassoLambdaMax(gram, moment, factors, &beta);
  }
  SolveLassoGram(gram, moment, lambda * factors, &beta, options.max_sweeps, options.tolerance);
  return beta;
}

bool CrossValidateLasso(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                        const Eigen::VectorXd& w, const std::vector<int>& group,
                        const LassoOptions& options, LassoPath* path, std::string* error) {
  const int n = static_cast<int>(x.rows()), p = static_cast<int>(x.cols());
  if (n == 0 || p == 0) {
    *error =
        "lasso: no samples or no columns (" + std::to_string(n) + " x " + std::to_string(p) + ")";
    return false;
  }
  if (y.size() != n || w.size() != n || static_cast<int>(group.size()) != n) {
    *error = "lasso: " + std::to_string(n) + " rows of regressors but " + std::to_string(y.size()) +
             " targets, " + std::to_string(w.size()) + " weights and " +
             std::to_string(group.size()) + " group ids";
    return false;
  }
  if (!x.allFinite() || !y.allFinite() || !w.allFinite()) {
    *error = "lasso: regressors, targets or weights are not finite";
    return false;
  }
  for (int i = 0; i < n; ++i) {
    if (!(w[i] > 0.0)) {
      *error = "lasso: weight " + std::to_string(i) + " is " + std::to_string(w[i]) +
               ", weights must be > 0";
      return false;
    }
  }
  if (!options.IsValid(p, error)) return false;
  std::map<int, int> index;
  std::vector<std::vector<int>> members;
  for (int i = 0; i < n; ++i) {
    const auto inserted = index.emplace(group[i], static_cast<int>(members.size()));
    if (inserted.second) members.emplace_back();
    members[inserted.first->second].push_back(i);
  }
  const int groups = static_cast<int>(members.size());
  if (groups < 2) {
    *error = "lasso: leave-one-group-out cross-validation needs at least 2 groups, not " +
             std::to_string(groups);
    return false;
  }

  // Each group's X'WX and X'Wy; the full ones are their sums.
  const Eigen::VectorXd factors = Factors(options, p);
  std::vector<Eigen::MatrixXd> group_x(groups), group_gram(groups);
  std::vector<Eigen::VectorXd> group_y(groups), group_w(groups), group_moment(groups);
  Eigen::MatrixXd raw_gram = Eigen::MatrixXd::Zero(p, p);
  Eigen::VectorXd raw_moment = Eigen::VectorXd::Zero(p);
  for (int g = 0; g < groups; ++g) {
    group_x[g] = x(members[g], Eigen::all);
    group_y[g] = y(members[g]);
    group_w[g] = w(members[g]);
    group_gram[g] = group_x[g].transpose() * group_w[g].asDiagonal() * group_x[g];
    group_moment[g] = group_x[g].transpose() * group_w[g].cwiseProduct(group_y[g]);
    raw_gram += group_gram[g];
    raw_moment += group_moment[g];
  }

  LassoPath r;
  r.groups = groups;
  const Eigen::MatrixXd gram = (2.0 / n) * raw_gram;
  const Eigen::VectorXd moment = (2.0 / n) * raw_moment;
  Eigen::VectorXd beta;
  r.lambda = LambdaGrid(LassoLambdaMax(gram, moment, factors, &beta), options);
  const int points = options.path_points;
  r.beta.resize(points, p);
  r.nonzero.resize(points);
  for (int k = 0; k < points; ++k) {
    r.sweeps += SolveLassoGram(gram, moment, r.lambda[k] * factors, &beta, options.max_sweeps,
                               options.tolerance);
    r.beta.row(k) = beta.transpose();
    r.nonzero[k] = static_cast<int>((beta.array() != 0.0).count());
  }

  // Folds: the full sums minus the left-out group's, on the fold's own N. A column the fold
  // leaves (numerically) empty is zeroed outright, so rounding cannot fit a coefficient to it.
  Eigen::MatrixXd squared_error(groups, points);  // sum over the group of W e^2
  Eigen::VectorXd group_weight(groups);
  for (int g = 0; g < groups; ++g) {
    const int kept = n - static_cast<int>(members[g].size());
    Eigen::MatrixXd fold_gram = (2.0 / kept) * (raw_gram - group_gram[g]);
    Eigen::VectorXd fold_moment = (2.0 / kept) * (raw_moment - group_moment[g]);
    for (int j = 0; j < p; ++j) {
      if (fold_gram(j, j) <= 1e-12 * gram(j, j)) {
        fold_gram.row(j).setZero();
        fold_gram.col(j).setZero();
        fold_moment[j] = 0.0;
      }
    }
    LassoLambdaMax(fold_gram, fold_moment, factors, &beta);
    group_weight[g] = group_w[g].sum();
    for (int k = 0; k < points; ++k) {
      r.sweeps += SolveLassoGram(fold_gram, fold_moment, r.lambda[k] * factors, &beta,
                                 options.max_sweeps, options.tolerance);
      squared_error(g, k) = (group_y[g] - group_x[g] * beta).cwiseAbs2().dot(group_w[g]);
    }
  }

  // Weighted mean over all left-out samples; SE from the spread of the groups' own means.
  const double total_weight = group_weight.sum();
  r.cv_error.resize(points);
  r.cv_standard_error.resize(points);
  for (int k = 0; k < points; ++k) {
    const double mean = squared_error.col(k).sum() / total_weight;
    double spread = 0.0;
    for (int g = 0; g < groups; ++g) {
      const double e = squared_error(g, k) / group_weight[g] - mean;
      spread += group_weight[g] * e * e;
    }
    r.cv_error[k] = mean;
    r.cv_standard_error[k] = std::sqrt(spread / total_weight / (groups - 1));
    if (r.best < 0 || mean < r.cv_error[r.best]) r.best = k;
  }
  const double limit = r.cv_error[r.best] + r.cv_standard_error[r.best];
  r.one_standard_error = 0;
  while (r.cv_error[r.one_standard_error] > limit) ++r.one_standard_error;
  *path = std::move(r);
  return true;
}

}  // namespace vesselid

// Weighted lasso: soft-thresholding on an orthogonal design, optimality (KKT) conditions on
// correlated and polynomial designs, lambda_max, unpenalised columns, the least-squares limit,
// leave-one-group-out CV against a brute-force refit per fold, support recovery, weights,
// and clear errors. Every expectation is computed from the data, not from the solver's Gram.
#include "engine/regression/lasso.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace lasso_test {

struct Data {
  Eigen::MatrixXd x;
  Eigen::VectorXd y, w;
  std::vector<int> group;
};

// AR(1)-correlated columns (corr(x_j, x_k) = rho^|j-k|) on scales 0.1, 1, 10; column 0 is an
// intercept. y = x beta + sigma noise; weights in [0.3, 3]; groups of `group_size` rows.
Data Correlated(int n, int p, double rho, const Eigen::VectorXd& beta, double sigma, int group_size,
                unsigned seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> weight(0.3, 3.0);
  Data d;
  d.x.resize(n, p);
  d.y.resize(n);
  d.w.resize(n);
  for (int i = 0; i < n; ++i) {
    d.x(i, 0) = 1.0;
    double previous = unit(random);
    for (int j = 1; j < p; ++j) {
      previous = rho * previous + std::sqrt(1.0 - rho * rho) * unit(random);
      d.x(i, j) = std::pow(10.0, j % 3 - 1) * previous;
    }
    d.y[i] = d.x.row(i).dot(beta) + sigma * unit(random);
    d.w[i] = weight(random);
    d.group.push_back(i / group_size);
  }
  return d;
}

Eigen::VectorXd RandomBeta(int p, unsigned seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  Eigen::VectorXd beta(p);
  for (int j = 0; j < p; ++j) beta[j] = unit(random) / std::pow(10.0, j % 3 - 1);
  return beta;
}

// Gradient of (1/N) sum_i w_i (y_i - x_i b)^2, straight from the data.
Eigen::VectorXd Gradient(const Data& d, const Eigen::VectorXd& b) {
  return -(2.0 / d.x.rows()) * d.x.transpose() * d.w.cwiseProduct(d.y - d.x * b);
}

// Expects the lasso optimality conditions at b, to a tolerance at the rounding scale of
// each gradient component. Returns the number of nonzero penalised coefficients.
int ExpectKkt(const Data& d, const Eigen::VectorXd& b, double lambda, const Eigen::VectorXd& f) {
  const double n = d.x.rows();
  const Eigen::VectorXd g = Gradient(d, b);
  const Eigen::VectorXd scale = (2.0 / n) * d.x.cwiseAbs().transpose() *
                                d.w.cwiseProduct(d.y.cwiseAbs() + d.x.cwiseAbs() * b.cwiseAbs());
  int nonzero = 0;
  for (int j = 0; j < b.size(); ++j) {
    const double tolerance = 1e-9 * scale[j];
    if (b[j] == 0.0) {
      EXPECT_LE(std::abs(g[j]), lambda * f[j] + tolerance) << "zero coefficient " << j;
    } else {
      EXPECT_NEAR(g[j], -lambda * f[j] * (b[j] > 0 ? 1.0 : -1.0), tolerance) << "coef " << j;
      if (f[j] > 0.0) ++nonzero;
    }
  }
  return nonzero;
}

LassoPath Path(const Data& d, const LassoOptions& options) {
  LassoPath path;
  std::string error;
  EXPECT_TRUE(CrossValidateLasso(d.x, d.y, d.w, d.group, options, &path, &error)) << error;
  return path;
}

TEST(Lasso, OrthogonalDesignIsSoftThresholding) {
  // Walsh columns: an intercept and +-c_j square waves, pairwise orthogonal with equal weights.
  const int n = 32, p = 5;
  const Eigen::VectorXd c = (Eigen::VectorXd(p) << 1.0, 0.5, 2.0, 3.0, 0.1).finished();
  Data d;
  d.x.resize(n, p);
  d.y.resize(n);
  d.w = Eigen::VectorXd::Constant(n, 2.5);
  std::mt19937_64 random(7);
  std::normal_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    d.x(i, 0) = c[0];
    for (int j = 1; j < p; ++j) d.x(i, j) = c[j] * ((i >> (j - 1)) & 1 ? 1.0 : -1.0);
    d.y[i] = 3.0 + 2.0 * unit(random);
  }
  LassoOptions options;
  options.penalty_factors = (Eigen::VectorXd(p) << 0.0, 1.0, 2.0, 0.5, 1.0).finished();
  for (double lambda : {0.0, 0.05, 0.3, 1.0, 4.0}) {
    const Eigen::VectorXd b = FitLasso(d.x, d.y, d.w, lambda, options);
    for (int j = 0; j < p; ++j) {
      // min a b^2 - 2 z b + lambda f |b|, a = mean w x^2, z = mean w x y.
      const double a = d.w.dot(d.x.col(j).cwiseAbs2()) / n;
      const double z = d.w.dot(d.x.col(j).cwiseProduct(d.y)) / n;
      const double shrunk = std::max(std::abs(z) - 0.5 * lambda * options.penalty_factors[j], 0.0);
      const double expected = std::copysign(shrunk, z) / a;
      EXPECT_NEAR(b[j], expected, 1e-12 * (1.0 + std::abs(expected))) << lambda << " " << j;
      if (expected == 0.0) {
        EXPECT_EQ(b[j], 0.0);
      }
    }
  }
}

TEST(Lasso, KktConditionsHoldAtRandomLambdas) {
  const int p = 12;
  Data d = Correlated(150, p, 0.8, RandomBeta(p, 11), 0.5, 3, 12);
  LassoOptions options;
  options.penalty_factors = Eigen::VectorXd::LinSpaced(p, 0.0, 2.0);
  options.path_points = 20;
  const LassoPath path = Path(d, options);
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> exponent(-4.0, 0.0);
  int sparse = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const double lambda = path.lambda[0] * std::pow(10.0, exponent(random));
    const int nonzero =
        ExpectKkt(d, FitLasso(d.x, d.y, d.w, lambda, options), lambda, options.penalty_factors);
    if (nonzero < p - 1) ++sparse;
  }
  EXPECT_GT(sparse, 0);  // the conditions were tested on both kinds of coefficient
  for (int k = 0; k < options.path_points; ++k) {
    ExpectKkt(d, path.beta.row(k).transpose(), path.lambda[k], options.penalty_factors);
  }

  // Seed 004's polynomial basis in (U, r): strongly correlated columns on scales 1 .. 1e4.
  std::mt19937_64 poly_random(14);
  std::uniform_real_distribution<double> speed(1.0, 10.0), rate(-0.3, 0.3);
  std::normal_distribution<double> unit(0.0, 1.0);
  Data poly;
  poly.x.resize(120, 15);
  poly.y.resize(120);
  poly.w = Eigen::VectorXd::Ones(120);
  for (int i = 0; i < 120; ++i) {
    const double u = speed(poly_random), r = rate(poly_random);
    int column = 0;
    for (int degree = 0; degree <= 4; ++degree) {
      for (int k = 0; k <= degree; ++k) {
        poly.x(i, column++) = std::pow(u, degree - k) * std::pow(r, k);
      }
    }
    poly.y[i] = 0.5 + 0.2 * u + 0.05 * u * u + 3.0 * r + 0.01 * unit(poly_random);
    poly.group.push_back(i / 4);
  }
  LassoOptions poly_options;
  poly_options.penalty_factors = Eigen::VectorXd::Ones(15);
  poly_options.penalty_factors[0] = 0.0;
  const LassoPath poly_path = Path(poly, poly_options);
  // Plain coordinate descent needs thousands of sweeps per fit on these columns; the
  // feature-sign steps finish in a few.
  const int fits = (poly_path.groups + 1) * poly_options.path_points;
  EXPECT_LT(poly_path.sweeps, 5 * fits) << poly_path.sweeps / double(fits) << " per fit";
  for (int k = 0; k < poly_options.path_points; k += 7) {
    ExpectKkt(poly, poly_path.beta.row(k).transpose(), poly_path.lambda[k],
              poly_options.penalty_factors);
  }
}

TEST(Lasso, LambdaMaxIsTheSmallestLambdaWithEveryPenalisedCoefficientZero) {
  const int p = 8;
  Data d = Correlated(90, p, 0.5, RandomBeta(p, 21), 1.0, 3, 22);
  LassoOptions options;
  options.penalty_factors = Eigen::VectorXd::Constant(p, 1.5);
  options.penalty_factors[0] = 0.0;  // the intercept
  const LassoPath path = Path(d, options);
  // Independently: the intercept alone fits the weighted mean; lambda_max is the largest
  // |gradient| / f of the penalised columns there.
  const double mean = d.w.dot(d.y) / d.w.sum();
  Eigen::VectorXd intercept_only = Eigen::VectorXd::Zero(p);
  intercept_only[0] = mean;
  const Eigen::VectorXd g = Gradient(d, intercept_only);
  const double lambda_max = g.tail(p - 1).cwiseAbs().maxCoeff() / 1.5;
  EXPECT_NEAR(path.lambda[0], lambda_max, 1e-12 * lambda_max);
  EXPECT_NEAR(path.lambda.back(), 1e-4 * lambda_max, 1e-15 * lambda_max);

  const Eigen::VectorXd at = FitLasso(d.x, d.y, d.w, path.lambda[0], options);
  EXPECT_EQ((at.tail(p - 1).array() != 0.0).count(), 0) << at.transpose();
  EXPECT_NEAR(at[0], mean, 1e-12 * std::abs(mean));
  EXPECT_EQ(path.nonzero[0], 1);
  const Eigen::VectorXd below = FitLasso(d.x, d.y, d.w, path.lambda[0] * (1.0 - 1e-6), options);
  EXPECT_EQ((below.tail(p - 1).array() != 0.0).count(), 1) << below.transpose();
  EXPECT_GT(path.nonzero[1], 1);
}

TEST(Lasso, UnpenalisedColumnIsNeverZero) {
  const int p = 6;
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(p);
  beta[0] = 3.0;
  beta[4] = 1e-3;  // column 4 (scale 0.1) barely matters
  Data d = Correlated(80, p, 0.3, beta, 1.0, 2, 31);
  LassoOptions options;
  options.penalty_factors = Eigen::VectorXd::Ones(p);
  options.penalty_factors[4] = 0.0;
  const LassoPath path = Path(d, options);
  for (int k = 0; k < options.path_points; ++k) {
    EXPECT_NE(path.beta(k, 4), 0.0) << k;
  }
  EXPECT_EQ(path.beta(0, 0), 0.0);  // penalised, the intercept is zero at lambda_max
}

TEST(Lasso, PathEndsAtWeightedLeastSquares) {
  const int p = 10;
  Data d = Correlated(100, p, 0.6, RandomBeta(p, 41), 0.3, 5, 42);
  LassoOptions options;
  options.path_ratio = 1e-9;
  options.path_points = 30;
  const LassoPath path = Path(d, options);
  const Eigen::MatrixXd xtwx = d.x.transpose() * d.w.asDiagonal() * d.x;
  const Eigen::VectorXd wls = xtwx.ldlt().solve(d.x.transpose() * d.w.cwiseProduct(d.y));
  const Eigen::VectorXd last = path.beta.row(options.path_points - 1).transpose();
  // With every coefficient nonzero, b = G^-1 (m - lambda f sign b), G = (2/N) X'WX: the
  // distance to least squares is bounded by lambda |G^-1| f and vanishes with lambda.
  const Eigen::MatrixXd inverse = ((2.0 / d.x.rows()) * xtwx).inverse();
  const Eigen::VectorXd bound = path.lambda.back() * inverse.cwiseAbs().rowwise().sum();
  for (int j = 0; j < p; ++j) {
    EXPECT_NEAR(last[j], wls[j], bound[j] + 1e-12 * std::abs(wls[j])) << j;
    EXPECT_LT(bound[j], 1e-5 * std::abs(wls[j])) << j;
  }
  EXPECT_EQ(path.nonzero.back(), p);
  for (size_t k = 1; k < path.lambda.size(); ++k) EXPECT_LT(path.lambda[k], path.lambda[k - 1]);
}

// Leave-one-group-out by brute force: refit on the rows outside each group.
struct BruteForce {
  std::vector<double> error, standard_error;
};
BruteForce BruteForceCv(const Data& d, const LassoPath& path, const LassoOptions& options) {
  const int n = static_cast<int>(d.x.rows());
  std::map<int, std::vector<int>> members;
  for (int i = 0; i < n; ++i) members[d.group[i]].push_back(i);
  const int points = static_cast<int>(path.lambda.size());
  std::vector<std::vector<double>> group_error(points), group_weight(points);
  BruteForce b;
  b.error.assign(points, 0.0);
  for (const auto& [id, rows] : members) {
    std::vector<int> train;
    for (int i = 0; i < n; ++i) {
      if (d.group[i] != id) train.push_back(i);
    }
    const Eigen::MatrixXd x = d.x(train, Eigen::all);
    const Eigen::VectorXd y = d.y(train), w = d.w(train);
    for (int k = 0; k < points; ++k) {
      const Eigen::VectorXd beta = FitLasso(x, y, w, path.lambda[k], options);
      const Eigen::VectorXd e = d.y(rows) - d.x(rows, Eigen::all) * beta;
      group_error[k].push_back(e.cwiseAbs2().dot(d.w(rows)) / d.w(rows).sum());
      group_weight[k].push_back(d.w(rows).sum());
    }
  }
  const double total = d.w.sum();
  const int groups = static_cast<int>(members.size());
  for (int k = 0; k < points; ++k) {
    double mean = 0.0, spread = 0.0;
    for (int g = 0; g < groups; ++g) mean += group_weight[k][g] * group_error[k][g] / total;
    for (int g = 0; g < groups; ++g) {
      spread += group_weight[k][g] * std::pow(group_error[k][g] - mean, 2) / total;
    }
    b.error[k] = mean;
    b.standard_error.push_back(std::sqrt(spread / (groups - 1)));
  }
  return b;
}

TEST(Lasso, GroupedCrossValidationLeavesDuplicatesOutTogether) {
  // 40 distinct samples, each stored twice (a steady-state point and its mirrored copy) in
  // one group; ids deliberately not contiguous or sorted.
  const int p = 8, distinct = 40;
  const Data base = Correlated(distinct, p, 0.5, RandomBeta(p, 51), 1.0, 1, 52);
  Data d;
  d.x.resize(2 * distinct, p);
  d.y.resize(2 * distinct);
  d.w.resize(2 * distinct);
  for (int i = 0; i < distinct; ++i) {
    for (int copy = 0; copy < 2; ++copy) {
      const int row = copy * distinct + i;
      d.x.row(row) = base.x.row(i);
      d.y[row] = base.y[i];
      d.w[row] = base.w[i];
    }
  }
  d.group.resize(2 * distinct);
  for (int row = 0; row < 2 * distinct; ++row) d.group[row] = 1000 - 7 * (row % distinct);
  LassoOptions options;
  options.penalty_factors = Eigen::VectorXd::Ones(p);
  options.penalty_factors[0] = 0.0;
  options.path_points = 15;
  const LassoPath path = Path(d, options);
  EXPECT_EQ(path.groups, distinct);
  const BruteForce brute = BruteForceCv(d, path, options);
  for (int k = 0; k < options.path_points; ++k) {
    EXPECT_NEAR(path.cv_error[k], brute.error[k], 1e-9 * brute.error[k]) << k;
    EXPECT_NEAR(path.cv_standard_error[k], brute.standard_error[k], 1e-8 * brute.standard_error[k])
        << k;
  }
  EXPECT_EQ(path.best,
            std::min_element(brute.error.begin(), brute.error.end()) - brute.error.begin());
  EXPECT_LE(path.one_standard_error, path.best);

  // Each copy in its own group: the twin in the training set leaks, and the unregularised
  // end looks better than it is.
  Data leaky = d;
  for (int row = 0; row < 2 * distinct; ++row) leaky.group[row] = row;
  const LassoPath leaky_path = Path(leaky, options);
  EXPECT_EQ(leaky_path.groups, 2 * distinct);
  EXPECT_LT(leaky_path.cv_error.back(), 0.9 * path.cv_error.back());
  const BruteForce leaky_brute = BruteForceCv(leaky, leaky_path, options);
  EXPECT_NEAR(leaky_path.cv_error.back(), leaky_brute.error.back(),
              1e-9 * leaky_brute.error.back());
}

TEST(Lasso, CrossValidationFindsTheSupportOfASparseTruth) {
  const int p = 16;  // an unpenalised intercept and 15 candidates, 3 of them in the truth
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(p);
  beta[0] = 1.0;
  beta[2] = 0.2;    // column scale 10: effect 2 noise sigmas
  beta[7] = -1.5;   // scale 1
  beta[12] = 10.0;  // scale 0.1
  Data d = Correlated(200, p, 0.4, beta, 1.0, 4, 61);
  LassoOptions options;
  options.penalty_factors = Eigen::VectorXd::Ones(p);
  options.penalty_factors[0] = 0.0;
  // Unit-free penalties: factors proportional to the column RMS (seed 004's scales differ).
  for (int j = 1; j < p; ++j) options.penalty_factors[j] = d.x.col(j).norm() / std::sqrt(200.0);
  const LassoPath path = Path(d, options);
  ASSERT_GT(path.best, 0);
  ASSERT_LT(path.best, options.path_points - 1);  // an interior minimum
  const int chosen = path.one_standard_error;
  for (int j = 1; j < p; ++j) {
    const bool truth = beta[j] != 0.0;
    EXPECT_EQ(path.beta(chosen, j) != 0.0, truth) << "column " << j << " at one SE";
    if (truth) {
      EXPECT_NE(path.beta(path.best, j), 0.0) << "column " << j << " at best";
    }
  }
  EXPECT_LE(path.nonzero[path.best], 1 + 3 + 4);  // few false positives at the CV minimum
  EXPECT_LT(path.cv_error[path.best], 0.5 * path.cv_error[0]);
}

TEST(Lasso, WeightsMatter) {
  const int p = 5;
  Data d = Correlated(60, p, 0.3, RandomBeta(p, 71), 0.2, 3, 72);
  LassoOptions options;
  const double lambda = 0.01;
  const Eigen::VectorXd clean = FitLasso(d.x, d.y, d.w, lambda, options);
  // One gross outlier appended: with a tiny weight it is invisible, with weight 1 it is not.
  // Dropping it instead changes N from 61 to 60, i.e. lambda by 61/60.
  Data outlier = d;
  outlier.x.conservativeResize(61, p);
  outlier.y.conservativeResize(61);
  outlier.w.conservativeResize(61);
  outlier.x.row(60) = d.x.row(0);
  outlier.y[60] = d.y[0] + 100.0;
  outlier.w[60] = 1e-14;
  const Eigen::VectorXd tiny = FitLasso(outlier.x, outlier.y, outlier.w, lambda, options);
  const Eigen::VectorXd dropped = FitLasso(d.x, d.y, d.w, lambda * 61.0 / 60.0, options);
  EXPECT_LT((tiny - dropped).cwiseAbs().maxCoeff(), 1e-9 * dropped.cwiseAbs().maxCoeff());
  outlier.w[60] = 1.0;
  const Eigen::VectorXd heavy = FitLasso(outlier.x, outlier.y, outlier.w, lambda, options);
  EXPECT_GT((heavy - clean).cwiseAbs().maxCoeff(), 0.1);

  // Scaling every weight scales the loss: lambdas scale with it, fits and CV errors do not.
  LassoOptions path_options;
  path_options.path_points = 10;
  const LassoPath once = Path(d, path_options);
  Data scaled = d;
  scaled.w *= 7.0;
  const LassoPath seven = Path(scaled, path_options);
  for (int k = 0; k < path_options.path_points; ++k) {
    EXPECT_NEAR(seven.lambda[k], 7.0 * once.lambda[k], 1e-12 * seven.lambda[k]);
    EXPECT_NEAR(seven.cv_error[k], once.cv_error[k], 1e-9 * once.cv_error[k]);
    EXPECT_LT((seven.beta.row(k) - once.beta.row(k)).cwiseAbs().maxCoeff(), 1e-9);
  }
}

TEST(Lasso, RejectsUnusableInput) {
  const Data d = Correlated(20, 3, 0.0, Eigen::Vector3d(1.0, 2.0, 3.0), 0.1, 5, 81);
  LassoPath path;
  std::string error;
  auto rejects = [&](const Data& data, const LassoOptions& options, const std::string& text) {
    error.clear();
    EXPECT_FALSE(CrossValidateLasso(data.x, data.y, data.w, data.group, options, &path, &error));
    EXPECT_NE(error.find(text), std::string::npos) << error;
  };
  Data bad = d;
  bad.y.conservativeResize(19);
  rejects(bad, {}, "20 rows of regressors but 19 targets");
  bad = d;
  bad.group.pop_back();
  rejects(bad, {}, "19 group ids");
  bad = d;
  bad.x(3, 1) = NAN;
  rejects(bad, {}, "not finite");
  bad = d;
  bad.w[4] = 0.0;
  rejects(bad, {}, "weight 4 is 0");
  bad = d;
  bad.w[5] = -1.0;
  rejects(bad, {}, "weights must be > 0");
  bad = d;
  bad.group.assign(20, 3);
  rejects(bad, {}, "at least 2 groups, not 1");
  LassoOptions options;
  options.penalty_factors = Eigen::VectorXd::Ones(2);
  rejects(d, options, "2 penalty factors for 3 columns");
  options.penalty_factors = Eigen::Vector3d(1.0, -1.0, 1.0);
  rejects(d, options, ">= 0");
  options.penalty_factors = Eigen::Vector3d::Zero();
  rejects(d, options, "nothing is penalised");
  options = {};
  options.path_points = 0;
  rejects(d, options, "path_points");
  options = {};
  options.path_ratio = 1.5;
  rejects(d, options, "path_ratio");
  options.path_ratio = 0.0;
  rejects(d, options, "path_ratio");
  EXPECT_TRUE(CrossValidateLasso(d.x, d.y, d.w, d.group, {}, &path, &error)) << error;
}

}  // namespace lasso_test
}  // namespace vesselid

// Equation-error least squares: exact recovery, standard errors against their formula,
// seed 003's robust weighting against gross outliers, ridge and lasso with cross-validated
// penalties, and clear errors.
#include "engine/regression/linear_regression.h"

#include <cmath>
#include <random>

#include "gtest/gtest.h"

namespace vesselid {
namespace linear_regression_test {

// y = 2 + 0.5 x1 - 3 x2 (+ 0 x3) + noise, x on very different scales.
struct Data {
  Eigen::MatrixXd x;
  Eigen::VectorXd y;
};

Data Make(int n, double sigma, bool irrelevant_column, unsigned seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  Data d;
  d.x.resize(n, irrelevant_column ? 4 : 3);
  d.y.resize(n);
  for (int i = 0; i < n; ++i) {
    d.x(i, 0) = 1.0;
    d.x(i, 1) = 100.0 * unit(random);
    d.x(i, 2) = 0.01 * unit(random);
    if (irrelevant_column) d.x(i, 3) = unit(random);
    d.y[i] = 2.0 + 0.5 * d.x(i, 1) - 3.0 * d.x(i, 2) + sigma * unit(random);
  }
  return d;
}

TEST(Regression, RecoversExactDataAndReportsTheLeastSquaresCovariance) {
  Data exact = Make(200, 0.0, false, 1);
  RegressionResult r;
  std::string error;
  ASSERT_TRUE(SolveRegression(exact.x, exact.y, {}, &r, &error)) << error;
  EXPECT_NEAR(r.theta[0], 2.0, 1e-10);
  EXPECT_NEAR(r.theta[1], 0.5, 1e-12);
  EXPECT_NEAR(r.theta[2], -3.0, 1e-8);
  EXPECT_NEAR(r.r2, 1.0, 1e-12);

  Data noisy = Make(500, 0.1, false, 2);
  ASSERT_TRUE(SolveRegression(noisy.x, noisy.y, {}, &r, &error)) << error;
  const Eigen::VectorXd e = noisy.y - noisy.x * r.theta;
  const double s2 = e.squaredNorm() / (500 - 3);
  const Eigen::MatrixXd expected = s2 * (noisy.x.transpose() * noisy.x).inverse();
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(r.std_errors[j], std::sqrt(expected(j, j)), 1e-9 * std::sqrt(expected(j, j)));
    EXPECT_LT(std::abs(r.theta[j] - Eigen::Vector3d(2.0, 0.5, -3.0)[j]), 4 * r.std_errors[j]);
  }
}

// Standard errors do not depend on the regressors' units: a propeller command logged in rpm
// (x 1000, its square x 1e6) gives the same estimates and standard errors, scaled by the same
// factors, as the +-1 command. Unscaled, the square in rpm^2 put the other columns below the
// pseudo-inverse's rank threshold and every standard error came out wrong.
TEST(Regression, StandardErrorsAreInvariantToTheScalingOfTheRegressors) {
  std::mt19937_64 random(5);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> command(-1.0, 1.0);
  const int n = 800;
  Eigen::MatrixXd x(n, 4), x_rpm(n, 4);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    const double u = 0.3 * unit(random), c = command(random);
    x.row(i) << u, std::abs(u) * u, c, std::abs(c) * c;
    y[i] = -0.8 * u - 0.2 * std::abs(u) * u + 0.4 * c + 0.6 * std::abs(c) * c + 0.05 * unit(random);
    x_rpm.row(i) << x(i, 0), x(i, 1), 1000.0 * c, 1e6 * std::abs(c) * c;
  }
  for (Penalty penalty : {Penalty::kNone, Penalty::kRidge}) {
    RegressionOptions options;
    options.penalty = penalty;
    options.lambda = penalty == Penalty::kRidge ? 1e-3 : -1.0;
    RegressionResult a, b;
    std::string error;
    ASSERT_TRUE(SolveRegression(x, y, options, &a, &error)) << error;
    ASSERT_TRUE(SolveRegression(x_rpm, y, options, &b, &error)) << error;
    // A covariance the stage can use (least_squares.cc weights the coefficients by its
    // Cholesky factor; without it every standard error falls back to the residual RMS).
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(b.covariance).info(), Eigen::Success);
    const Eigen::Vector4d factor(1.0, 1.0, 1000.0, 1e6);
    for (int j = 0; j < 4; ++j) {
      EXPECT_NEAR(b.theta[j] * factor[j], a.theta[j], 1e-6 * std::abs(a.theta[j])) << j;
      EXPECT_NEAR(b.std_errors[j] * factor[j], a.std_errors[j], 1e-6 * a.std_errors[j]) << j;
      if (j != 1) {  // not sigma
        EXPECT_LT(a.std_errors[j], 0.2 * std::abs(a.theta[j])) << j;
      }
    }
  }
}

TEST(Regression, RobustWeightingRejectsGrossOutliers) {
  Data d = Make(1000, 0.1, false, 3);
  for (int i = 0; i < 1000; i += 20) d.y[i] += 25.0;  // 5 % one-sided spikes
  RegressionResult plain, robust;
  std::string error;
  ASSERT_TRUE(SolveRegression(d.x, d.y, {}, &plain, &error)) << error;
  RegressionOptions options;
  options.robust = true;
  ASSERT_TRUE(SolveRegression(d.x, d.y, options, &robust, &error)) << error;
  EXPECT_GT(std::abs(plain.theta[0] - 2.0), 1.0);  // the spikes bias the intercept
  EXPECT_LT(std::abs(robust.theta[0] - 2.0), 0.05);
  EXPECT_LT(std::abs(robust.theta[2] + 3.0), 4 * robust.std_errors[2]);
  EXPECT_EQ(robust.rejected, 50);
  for (int i = 0; i < 1000; i += 20) EXPECT_EQ(robust.weights[i], 0.0);
}

TEST(Regression, LassoRemovesAnIrrelevantRegressorRidgeShrinks) {
  Data d = Make(400, 0.5, true, 4);
  RegressionOptions lasso;
  lasso.penalty = Penalty::kLasso;
  lasso.lambda = 20.0;
  RegressionResult r;
  std::string error;
  ASSERT_TRUE(SolveRegression(d.x, d.y, lasso, &r, &error)) << error;
  EXPECT_EQ(r.theta[3], 0.0);
  EXPECT_TRUE(std::isnan(r.std_errors[0]));
  EXPECT_NEAR(r.theta[1], 0.5, 0.01);

  RegressionOptions ridge;
  ridge.penalty = Penalty::kRidge;
  ridge.lambda = 1e5;  // overwhelming: every standardised coefficient shrinks towards 0
  ASSERT_TRUE(SolveRegression(d.x, d.y, ridge, &r, &error)) << error;
  EXPECT_LT(std::abs(r.theta[1]), 0.1);
  ridge.lambda = -1.0;  // cross-validated: well-conditioned data need almost no penalty
  ASSERT_TRUE(SolveRegression(d.x, d.y, ridge, &r, &error)) << error;
  EXPECT_NEAR(r.theta[1], 0.5, 0.01);
  EXPECT_NEAR(r.theta[2], -3.0, 4 * r.std_errors[2]);
  EXPECT_GE(r.lambda, 0.0);
}

TEST(Regression, RejectsUnusableInput) {
  RegressionResult r;
  std::string error;
  EXPECT_FALSE(SolveRegression(Eigen::MatrixXd::Ones(3, 3), Eigen::VectorXd::Ones(3), {}, &r,
                               &error));
  EXPECT_NE(error.find("3 samples for 3 parameters"), std::string::npos) << error;
  EXPECT_FALSE(SolveRegression(Eigen::MatrixXd::Ones(5, 2), Eigen::VectorXd::Ones(4), {}, &r,
                               &error));
  EXPECT_NE(error.find("5 rows of regressors but 4 targets"), std::string::npos) << error;
  Eigen::MatrixXd x = Eigen::MatrixXd::Ones(5, 2);
  x(2, 1) = NAN;
  EXPECT_FALSE(SolveRegression(x, Eigen::VectorXd::Ones(5), {}, &r, &error));
  EXPECT_NE(error.find("not finite"), std::string::npos) << error;
}

}  // namespace linear_regression_test
}  // namespace vesselid

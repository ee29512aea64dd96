// The HAC long-run covariance on a linear regression y = b x + e whose regressor and errors
// are both AR(1): the OLS slope's variance is, for large T,
//   Var(b) = LRV(x e) / (T^2 sx^4),   LRV(x e) = sx^2 se^2 (1 + rx re) / (1 - rx re),
// sx^2 = 1 / (1 - rx^2), se^2 = 1 / (1 - re^2) (unit innovations), which white-residual
// least squares (s^2 / sum x^2) understates by (1 + rx re) / (1 - rx re).
#include "engine/solve/hac_covariance.h"

#include <cmath>
#include <random>

#include "engine/solve/covariance.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace hac_covariance_test {

struct Replicates {
  double slope_variance = 0.0;  // spread of the estimates over the replicates
  double hac_variance = 0.0;    // mean HAC estimate
  double white_variance = 0.0;  // mean s^2 / sum x^2
};

Replicates Simulate(const HacOptions& options, double rx, double re, int length, int count) {
  std::mt19937 random(21);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> slopes;
  Replicates out;
  for (int k = 0; k < count; ++k) {
    Eigen::VectorXd x(length), y(length);
    double xt = normal(random) / std::sqrt(1 - rx * rx), et = normal(random) / std::sqrt(1 - re * re);
    for (int t = 0; t < length; ++t) {
      xt = rx * xt + normal(random);
      et = re * et + normal(random);
      x[t] = xt;
      y[t] = 2.0 * xt + et;
    }
    const double a = x.squaredNorm();
    const double b = x.dot(y) / a;
    const Eigen::VectorXd r = y - b * x;
    const Eigen::MatrixXd scores = (x.array() * r.array()).matrix();
    const Eigen::MatrixXd omega = LongRunCovariance(options, scores, nullptr);
    slopes.push_back(b);
    out.hac_variance += omega(0, 0) / (a * a) / count;
    out.white_variance += r.squaredNorm() / (length - 1) / a / count;
  }
  double mean = 0.0;
  for (double s : slopes) mean += s / count;
  for (double s : slopes) out.slope_variance += (s - mean) * (s - mean) / (count - 1);
  return out;
}

double Analytic(double rx, double re, int length) {
  const double sx2 = 1 / (1 - rx * rx), se2 = 1 / (1 - re * re);
  return sx2 * se2 * (1 + rx * re) / (1 - rx * re) / (length * sx2 * length * sx2 / length);
}

TEST(HacCovariance, MatchesTheLongRunVarianceOfAnAr1Regression) {
  const double rx = 0.6, re = 0.8;
  const int length = 4000, count = 150;
  const double truth = Analytic(rx, re, length);
  for (HacOptions::Kernel kernel :
       {HacOptions::Kernel::kBartlett, HacOptions::Kernel::kQuadraticSpectral}) {
    for (bool prewhiten : {true, false}) {
      HacOptions options;
      options.kernel = kernel;
      options.prewhiten = prewhiten;
      const Replicates r = Simulate(options, rx, re, length, count);
      SCOPED_TRACE(std::string(HacKernelToString(kernel)) + (prewhiten ? " prewhitened" : ""));
      // The replicates' spread agrees with the analytic variance (a check of the set-up) ...
      EXPECT_NEAR(r.slope_variance / truth, 1.0, 0.25);
      // ... the HAC estimate with both, within its known small downward bias ...
      EXPECT_NEAR(r.hac_variance / truth, 1.0, prewhiten ? 0.1 : 0.2);
      // ... while white-residual least squares is short by (1 + rx re) / (1 - rx re) = 2.8.
      EXPECT_NEAR(truth / r.white_variance, (1 + rx * re) / (1 - rx * re), 0.3);
    }
  }
}

// White scores: the long-run covariance is the lag-0 one. Node by node with the plug-in's
// short bandwidth in one series; aggregated over sqrt(T) blocks (fewer, noisier sums) on
// average over 40 series.
TEST(HacCovariance, WhiteScoresKeepTheirVariance) {
  std::mt19937 random(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int aggregation : {1, 0}) {
    SCOPED_TRACE(aggregation);
    HacOptions options;
    options.aggregation = aggregation;
    const int series = aggregation == 1 ? 1 : 40;
    Eigen::MatrixXd omega = Eigen::MatrixXd::Zero(2, 2), gram = Eigen::MatrixXd::Zero(2, 2);
    for (int k = 0; k < series; ++k) {
      Eigen::MatrixXd scores(20000, 2);
      for (int t = 0; t < scores.rows(); ++t) {
        scores(t, 0) = normal(random);
        scores(t, 1) = 0.5 * scores(t, 0) + normal(random);
      }
      double bandwidth = 0.0;
      omega += LongRunCovariance(options, scores, &bandwidth);
      gram += scores.transpose() * scores;
      if (aggregation == 1) {
        EXPECT_LT(bandwidth, 5.0);
      }
    }
    EXPECT_NEAR(omega(0, 0) / gram(0, 0), 1.0, 0.05);
    EXPECT_NEAR(omega(1, 1) / gram(1, 1), 1.0, 0.05);
    EXPECT_NEAR(omega(0, 1) / gram(0, 1), 1.0, 0.1);
  }
}

TEST(HacCovariance, FixedBandwidthUsesBartlettWeights) {
  // g = (1, 1, 1, 1): Gamma_0 = 4, Gamma_1 = 3, Gamma_2 = 2; S = 3: 4 + 2 (2/3 3 + 1/3 2).
  HacOptions options;
  options.prewhiten = false;
  options.aggregation = 1;
  options.bandwidth = 3.0;
  const Eigen::MatrixXd scores = Eigen::MatrixXd::Ones(4, 1);
  EXPECT_NEAR(LongRunCovariance(options, scores, nullptr)(0, 0), 4.0 + 2.0 * (2.0 + 2.0 / 3.0),
              1e-12);
}

// A sandwich covariance that is not positive semi-definite in floating point (a near-singular
// Hessian between two estimates) gives correlations within [-1, 1], at the limit.
TEST(HacCovariance, CorrelationStaysWithinPlusMinusOne) {
  Uncertainty u;
  u.variables = {0, 1, 2};
  u.covariance.resize(3, 3);
  u.covariance << 1.0, 1.62, 0.1, 1.62, 1.0, -0.2, 0.1, -0.2, 4.0;
  SetStdErrorsAndCorrelation(&u);
  EXPECT_DOUBLE_EQ(u.correlation(0, 1), 1.0);
  EXPECT_DOUBLE_EQ(u.correlation(1, 0), 1.0);
  EXPECT_DOUBLE_EQ(u.correlation(0, 2), 0.05);
  EXPECT_DOUBLE_EQ(u.correlation(1, 2), -0.1);
  EXPECT_DOUBLE_EQ(u.std_errors[2], 2.0);
}

}  // namespace hac_covariance_test
}  // namespace vesselid

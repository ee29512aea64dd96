// Fusion rules for shared parameters: mean, per-parameter inverse variance, and joint
// information fusion, on cases where they differ.
#include "engine/run/fusion.h"

#include <cmath>

#include "gtest/gtest.h"

namespace vesselid {
namespace fusion_test {

TEST(FuseEstimates, InverseVarianceAndMeanDiffer) {
  double value, std_error;
  std::string rule;
  FuseEstimates({1.0, 3.0}, {0.1, 0.3}, FusionRule::kInverseVariance, &value, &std_error, &rule);
  EXPECT_NEAR(value, (1.0 / 0.01 + 3.0 / 0.09) / (1 / 0.01 + 1 / 0.09), 1e-12);
  EXPECT_NEAR(std_error, 1 / std::sqrt(1 / 0.01 + 1 / 0.09), 1e-12);
  EXPECT_EQ(rule, "inverse_variance");
  FuseEstimates({1.0, 3.0}, {0.1, 0.3}, FusionRule::kMean, &value, &std_error, &rule);
  EXPECT_DOUBLE_EQ(value, 2.0);
  EXPECT_NEAR(std_error, std::sqrt(0.01 + 0.09) / 2, 1e-12);
  EXPECT_EQ(rule, "mean");
}

TEST(FuseEstimates, FallsBackToTheMeanWithoutStandardErrors) {
  double value, std_error;
  std::string rule;
  FuseEstimates({1.0, 3.0}, {0.1, NAN}, FusionRule::kInverseVariance, &value, &std_error, &rule);
  EXPECT_DOUBLE_EQ(value, 2.0);
  EXPECT_TRUE(std::isnan(std_error));
  EXPECT_EQ(rule, "mean (a stage has no standard error)");
}

// Stage 1 measures a alone (a = 1, variance 1); stage 2 measures a and b together
// (a = 3, b = 5, variances 1, correlation 0.8). Per parameter, b stays 5. Jointly, stage 1's
// news about a moves b along the correlation: the Gaussian update gives
//   a = 3 + 1/2 (1 - 3) = 2,  b = 5 + 0.8/2 (1 - 3) = 4.2,  var a = 1/2,  var b = 1 - 0.64/2.
TEST(FuseJointly, CorrelatedEstimatesMoveTogether) {
  SharedEstimate first;
  first.parameters = {0};
  first.value = Eigen::VectorXd::Constant(1, 1.0);
  first.covariance = Eigen::MatrixXd::Identity(1, 1);
  SharedEstimate second;
  second.parameters = {0, 1};
  second.value = Eigen::Vector2d(3.0, 5.0);
  second.covariance = (Eigen::Matrix2d() << 1.0, 0.8, 0.8, 1.0).finished();
  Eigen::VectorXd value;
  Eigen::MatrixXd covariance;
  ASSERT_TRUE(FuseJointly(2, {first, second}, &value, &covariance));
  EXPECT_NEAR(value[0], 2.0, 1e-12);
  EXPECT_NEAR(value[1], 4.2, 1e-12);
  EXPECT_NEAR(covariance(0, 0), 0.5, 1e-12);
  EXPECT_NEAR(covariance(1, 1), 0.68, 1e-12);
  // Per-parameter inverse variance leaves b where stage 2 put it.
  double b, std_error;
  std::string rule;
  FuseEstimates({5.0}, {1.0}, FusionRule::kInverseVariance, &b, &std_error, &rule);
  EXPECT_DOUBLE_EQ(b, 5.0);
}

TEST(FuseJointly, ParameterNoStageDeterminesIsSingular) {
  SharedEstimate only_a;
  only_a.parameters = {0};
  only_a.value = Eigen::VectorXd::Constant(1, 1.0);
  only_a.covariance = Eigen::MatrixXd::Identity(1, 1);
  Eigen::VectorXd value;
  Eigen::MatrixXd covariance;
  EXPECT_FALSE(FuseJointly(2, {only_a}, &value, &covariance));
}

TEST(FusionRule, NamesRoundTrip) {
  for (FusionRule r : {FusionRule::kInverseVariance, FusionRule::kMean, FusionRule::kInformation}) {
    FusionRule parsed;
    ASSERT_TRUE(StringToFusionRule(FusionRuleToString(r), &parsed));
    EXPECT_EQ(parsed, r);
  }
  FusionRule parsed;
  EXPECT_FALSE(StringToFusionRule("median", &parsed));
}

}  // namespace fusion_test
}  // namespace vesselid

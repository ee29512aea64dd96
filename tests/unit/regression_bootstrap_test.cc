// Bootstrap over CV groups (group_bootstrap.h, least_squares_bootstrap.h). The least-squares
// cases regress first-order Nomoto on data whose structure differs: yaw rates of a Norrbin
// ship (cubic term n3 r^3 the first-order model lacks) with white noise on the rate's
// derivative.
#include <cmath>
#include <random>

#include "engine/output/bootstrap_report.h"
#include "engine/output/stage_result_archive.h"
#include "engine/regression/group_bootstrap.h"
#include "engine/regression/least_squares_bootstrap.h"
#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"

namespace vesselid {
namespace regression_bootstrap_test {

TEST(GroupBootstrap, MeanOfGroupsHasTheTextbookStandardErrorAndIgnoresThreads) {
  // 40 groups of 5 samples; the quantity is the mean of the drawn samples. Its bootstrap SE
  // is sd(group means) sqrt((G - 1) / G) / sqrt(G) up to the Monte Carlo error of the runs.
  const int groups = 40;
  std::mt19937 random(3);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> group_mean(groups);
  for (double& m : group_mean) m = 2.0 + gauss(random);
  double mean = 0.0, square = 0.0;
  for (double m : group_mean) mean += m / groups;
  for (double m : group_mean) square += (m - mean) * (m - mean) / groups;
  const double expected = std::sqrt(square / groups);
  auto replicate = [&](const std::vector<int>& counts, std::vector<double>* values,
                       std::vector<double>* coefficients) {
    double sum = 0.0;
    int n = 0;
    for (int g = 0; g < groups; ++g) {
      sum += counts[g] * group_mean[g];
      n += counts[g];
    }
    values->push_back(sum / n);
    coefficients->push_back(counts[0] == 0 ? 0.0 : 1.0);  // zero when group 0 is not drawn
    return true;
  };
  GroupBootstrapOptions options;
  options.runs = 2000;
  options.threads = 1;
  BootstrapSummary one, four;
  std::string error;
  ASSERT_TRUE(RunGroupBootstrap({groups}, {"mean"}, {"group 0 drawn"}, replicate, options, &one,
                                &error)) << error;
  options.threads = 4;
  ASSERT_TRUE(RunGroupBootstrap({groups}, {"mean"}, {"group 0 drawn"}, replicate, options, &four,
                                &error)) << error;
  EXPECT_NEAR(one.std_error[0], expected, 0.06 * expected);
  EXPECT_LT(one.lower[0], mean);
  EXPECT_GT(one.upper[0], mean);
  EXPECT_NEAR(one.upper[0] - one.lower[0], 2 * 1.96 * expected, 0.1 * 2 * 1.96 * expected);
  // P(group 0 never drawn) = (1 - 1/G)^G.
  EXPECT_NEAR(one.zero_share[0], std::pow(1.0 - 1.0 / groups, groups), 0.03);
  EXPECT_EQ(one.std_error, four.std_error);
  EXPECT_EQ(one.lower, four.lower);
  EXPECT_EQ(one.zero_share, four.zero_share);
  EXPECT_EQ(one.groups, groups);

  // A checkpoint keeps it: a resumed run reports the same bootstrap.
  StageResult stage;
  stage.bootstrap = one;
  stage.bootstrap.resampled = "groups";
  StageResult restored;
  ASSERT_TRUE(StageResultFromArchive(
      nlohmann::json::from_cbor(nlohmann::json::to_cbor(StageResultToArchive(stage))), &restored,
      &error)) << error;
  EXPECT_EQ(BootstrapToJson(restored.bootstrap), BootstrapToJson(stage.bootstrap));
  EXPECT_EQ(BootstrapText(restored), BootstrapText(stage));
}

TEST(GroupBootstrap, StrataAreDrawnSeparatelyAndFailuresCounted) {
  GroupBootstrapOptions options;
  options.runs = 50;
  BootstrapSummary summary;
  std::string error;
  auto replicate = [](const std::vector<int>& counts, std::vector<double>* values,
                      std::vector<double>*) {
    int first = 0, second = 0;
    for (int g = 0; g < 3; ++g) first += counts[g];
    for (int g = 3; g < 10; ++g) second += counts[g];
    EXPECT_EQ(first, 3);
    EXPECT_EQ(second, 7);
    if (counts[0] == 3) return false;  // an unfittable draw
    values->push_back(counts[0]);
    return true;
  };
  ASSERT_TRUE(RunGroupBootstrap({3, 7}, {"count"}, {}, replicate, options, &summary, &error));
  EXPECT_EQ(summary.groups, 10);
  EXPECT_EQ(summary.runs, 50);
  EXPECT_GE(summary.failed, 0);
  EXPECT_LE(summary.upper[0], 2.0);  // the failed draws (count 3) are left out
  options.runs = 1;
  EXPECT_FALSE(RunGroupBootstrap({3}, {"count"}, {}, replicate, options, &summary, &error));
  EXPECT_NE(error.find("runs must be 0 (none) or >= 2"), std::string::npos) << error;
}

// One record of Norrbin yaw rates (T 8 s, K 0.12, n3, delta_0 0.01), derivative with white
// noise of `noise`.
std::vector<RegressionRecord> NorrbinRecords(double n3, double noise, unsigned seed) {
  auto norrbin = nomoto::MakeNorrbinHandle();
  const std::vector<double> truth = {8.0, 0.12, n3, 0.01};
  std::mt19937 random(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  RegressionRecord r;
  r.dt = 0.5;
  const int n = 4000;
  r.x = Eigen::MatrixXd::Zero(n, 2);
  r.xdot = Eigen::MatrixXd::Zero(n, 2);
  r.u.resize(n, 1);
  for (int k = 0; k < n; ++k) {
    r.t.push_back(0.5 * k);
    r.u(k, 0) = 0.2 * std::sin(0.05 * k) + 0.1 * std::sin(0.31 * k + 1.0);
    r.x(k, 1) = 0.03 * std::cos(0.07 * k) + 0.01 * std::sin(0.4 * k) + 0.02 * std::sin(0.013 * k);
    double xdot[2];
    const double x[2] = {0.0, r.x(k, 1)};
    norrbin->Derivative(x, &r.u(k, 0), truth.data(), xdot);
    r.xdot(k, 1) = xdot[1] + noise * gauss(random);
    r.region.push_back(0);
    r.use.push_back(true);
  }
  return {r};
}

std::vector<ParameterSpec> Specs(const ModelHandle& model) {
  std::vector<ParameterSpec> specs;
  const ModelInfo& info = model.info();
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    ParameterSpec s;
    s.name = info.parameters[i];
    s.start = info.parameter_defaults[i];
    specs.push_back(s);
  }
  return specs;
}

TEST(LeastSquaresBootstrap, OlsBootstrapAgreesWithTheAnalyticStandardErrors) {
  auto model = nomoto::MakeFirstOrderHandle();
  std::vector<RegressionRecord> records = NorrbinRecords(10.0, 3e-4, 5);
  const std::vector<ParameterSpec> specs = Specs(*model);
  LeastSquaresOptions options;
  options.bootstrap.runs = 400;
  options.bootstrap.blocks = 50;
  LeastSquaresResult fit;
  LeastSquaresSummary summary;
  ASSERT_TRUE(RunLeastSquares(*model, specs, options, &records, &fit, &summary)) << summary.message;
  BootstrapSummary bootstrap, threads;
  std::string error;
  options.bootstrap.threads = 1;
  ASSERT_TRUE(BootstrapLeastSquares(*model, specs, options, records, fit, summary, &bootstrap,
                                    &error)) << error;
  ASSERT_EQ(bootstrap.names.size(), specs.size());
  for (size_t i = 0; i < specs.size(); ++i) {
    ASSERT_EQ(bootstrap.names[i], specs[i].name);
    const double ratio = bootstrap.std_error[i] / fit.std_errors[i];
    EXPECT_GT(ratio, 0.75) << specs[i].name;
    EXPECT_LT(ratio, 1.25) << specs[i].name;
    EXPECT_LT(bootstrap.lower[i], fit.values[i]) << specs[i].name;
    EXPECT_GT(bootstrap.upper[i], fit.values[i]) << specs[i].name;
  }
  EXPECT_EQ(bootstrap.failed, 0);
  EXPECT_TRUE(bootstrap.zero_share.empty());  // no lasso
  options.bootstrap.threads = 3;
  ASSERT_TRUE(BootstrapLeastSquares(*model, specs, options, records, fit, summary, &threads,
                                    &error)) << error;
  EXPECT_EQ(bootstrap.std_error, threads.std_error);
  EXPECT_EQ(bootstrap.upper, threads.upper);
}

// A stronger cubic leaves a slowly varying misfit in the residuals, correlated over many
// samples: the blocks carry it, the analytic s^2 (X'X)^-1 (white residuals) does not.
TEST(LeastSquaresBootstrap, BlocksSeeTheCorrelatedMisfitTheAnalyticErrorsMiss) {
  auto model = nomoto::MakeFirstOrderHandle();
  std::vector<RegressionRecord> records = NorrbinRecords(30.0, 3e-4, 5);
  const std::vector<ParameterSpec> specs = Specs(*model);
  LeastSquaresOptions options;
  options.bootstrap.runs = 400;
  options.bootstrap.blocks = 50;
  LeastSquaresResult fit;
  LeastSquaresSummary summary;
  ASSERT_TRUE(RunLeastSquares(*model, specs, options, &records, &fit, &summary)) << summary.message;
  BootstrapSummary bootstrap;
  std::string error;
  ASSERT_TRUE(BootstrapLeastSquares(*model, specs, options, records, fit, summary, &bootstrap,
                                    &error)) << error;
  EXPECT_GT(bootstrap.std_error[0] / fit.std_errors[0], 1.4);  // T
}

TEST(LeastSquaresBootstrap, LassoStandardErrorsAreFiniteAndPositive) {
  auto model = nomoto::MakeFirstOrderHandle();
  std::vector<RegressionRecord> records = NorrbinRecords(30.0, 3e-4, 6);
  const std::vector<ParameterSpec> specs = Specs(*model);
  for (bool hold : {true, false}) {
    LeastSquaresOptions options;
    options.regression.penalty = Penalty::kLasso;
    options.bootstrap.runs = 40;
    options.bootstrap.hold_lambda = hold;
    LeastSquaresResult fit;
    LeastSquaresSummary summary;
    ASSERT_TRUE(RunLeastSquares(*model, specs, options, &records, &fit, &summary))
        << summary.message;
    BootstrapSummary bootstrap;
    std::string error;
    ASSERT_TRUE(BootstrapLeastSquares(*model, specs, options, records, fit, summary, &bootstrap,
                                      &error)) << error;
    EXPECT_EQ(bootstrap.lambda_held, hold);
    for (size_t i = 0; i < specs.size(); ++i) {
      EXPECT_TRUE(std::isfinite(bootstrap.std_error[i])) << specs[i].name;
      EXPECT_GT(bootstrap.std_error[i], 0.0) << specs[i].name;
    }
    ASSERT_FALSE(bootstrap.coefficient_names.empty());
    for (double share : bootstrap.zero_share) {
      EXPECT_GE(share, 0.0);
      EXPECT_LE(share, 1.0);
    }
  }
}

}  // namespace regression_bootstrap_test
}  // namespace vesselid

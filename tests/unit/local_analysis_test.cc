// Local analysis at the optimum: the Schur-complement standard errors agree with Ceres'
// covariance, an exchangeable pair at its ridge shows as an undetermined direction naming
// both, and sensitivities of a well-excited experiment are finite and positive.
#include "engine/solve/local_analysis.h"

#include <cmath>

#include "engine/solve/stage.h"
#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace local_analysis_test {

// The patrol vessel's steering loop with a multi-sine heading set point and 0.1 deg noise.
nomoto::ClosedLoopOptions MultisineLoop(unsigned seed) {
  nomoto::ClosedLoopOptions loop;
  loop.controller_gain = 0.7;
  loop.duration = 120.0;
  loop.sample_time = 0.05;
  loop.excitation.type = nomoto::Excitation::Type::kMultisine;
  loop.excitation.amplitude = 25.0 * M_PI / 180.0;
  loop.excitation.periods = {60.0, 23.0, 11.0, 5.0, 2.3};
  loop.heading_noise = 0.1 * M_PI / 180.0;
  loop.seed = seed;
  return loop;
}

std::vector<ParameterSpec> SecondOrderSpecs(const std::vector<double>& start) {
  const char* names[] = {"T1", "T2", "T3", "K", "delta_0"};
  std::vector<ParameterSpec> specs;
  for (int i = 0; i < 5; ++i) {
    ParameterSpec s;
    s.name = names[i];
    s.start = start[i];
    s.scale = i == 4 ? 0.01 : 0.0;
    s.role = i == 4 ? ParameterRole::kPerExperiment : ParameterRole::kFree;
    specs.push_back(s);
  }
  return specs;
}

class LocalAnalysisTest : public ::testing::Test {
 protected:
  std::unique_ptr<ModelHandle> model_ = nomoto::MakeSecondOrderHandle();

  // Two experiments sharing T1..K, each with its own rudder bias and initial heading.
  std::unique_ptr<OutputErrorProblem> TwoExperiments(const std::vector<double>& truth,
                                                     const std::vector<double>& start) {
    std::vector<double> other = truth;
    other[4] = -truth[4];
    std::vector<Experiment> runs = {
        testing::MakeExperiment(*model_, truth, MultisineLoop(1), Interpolation::kCubic, "a"),
        testing::MakeExperiment(*model_, other, MultisineLoop(2), Interpolation::kCubic, "b")};
    OutputErrorOptions options;
    options.free_initial_states = {"psi"};
    std::string error;
    auto problem =
        OutputErrorProblem::Create(model_.get(), runs, SecondOrderSpecs(start), options, &error);
    EXPECT_NE(problem, nullptr) << error;
    return problem;
  }
};

TEST_F(LocalAnalysisTest, SchurStandardErrorsAgreeWithCovarianceAndSensitivitiesArePositive) {
  const std::vector<double> truth = {2.0875, 0.3179, 0.1830, -0.1724, 0.01};
  auto problem = TwoExperiments(truth, {2.5, 0.25, 0.25, -0.12, 0.0});
  ASSERT_NE(problem, nullptr);
  StageSummary summary;
  ASSERT_TRUE(RunStage(StageOptions(), problem.get(), &summary)) << summary.message;
  ASSERT_TRUE(summary.uncertainty.available) << summary.uncertainty.message;
  const LocalAnalysis& a = summary.analysis;
  ASSERT_TRUE(a.available) << a.message;
  EXPECT_EQ(a.names, (std::vector<std::string>{"T1", "T2", "T3", "K"}));
  EXPECT_EQ(a.profiled, 4);  // delta_0 and the initial heading of each experiment
  EXPECT_NEAR(a.residual_variance, summary.uncertainty.residual_variance,
              1e-12 * a.residual_variance);
  for (size_t i = 0; i < a.parameters.size(); ++i) {
    const double reference = summary.uncertainty.StdError(a.parameters[i]);
    EXPECT_NEAR(a.std_errors[i], reference, 1e-3 * reference) << a.names[i];
  }
  EXPECT_TRUE(std::isfinite(a.condition_number));
  ASSERT_FALSE(a.directions.empty());  // the weakest direction is always reported
  EXPECT_LT(a.directions[0].eigenvalue_ratio, 1.0);
  EXPECT_GT(a.directions[0].std_dev, 0.0);

  ASSERT_EQ(a.channels, std::vector<std::string>{"psi"});
  for (int i = 0; i < a.sensitivity.cols(); ++i) {
    EXPECT_TRUE(std::isfinite(a.sensitivity(0, i)) && a.sensitivity(0, i) > 0) << a.names[i];
    EXPECT_TRUE(std::isfinite(a.noise_sensitivity(0, i)) && a.noise_sensitivity(0, i) > 0)
        << a.names[i];
  }
  // The heading change after t0 is proportional to K: a 1 % change of K changes it by 1 %,
  // measured against the heading's spread about its mean (smaller than about psi(t0)).
  EXPECT_GT(a.sensitivity(0, 3), 0.9);
  EXPECT_LT(a.sensitivity(0, 3), 3.0);
}

TEST_F(LocalAnalysisTest, ExchangeableRidgeIsAnUndeterminedDirectionNamingBoth) {
  // At T1 = T2 the model is symmetric in them, so dr/dT1 = dr/dT2: T1 - T2 is not determined
  // to first order. Analysed at the truth (with noise: s > 0), without solving.
  const std::vector<double> truth = {1.2, 1.2, 0.1830, -0.1724, 0.01};
  auto problem = TwoExperiments(truth, truth);
  ASSERT_NE(problem, nullptr);
  LocalAnalysis a;
  ASSERT_TRUE(ComputeLocalAnalysis(LocalAnalysisOptions(), problem.get(), &a)) << a.message;
  EXPECT_GT(a.condition_number, 1e6);
  ASSERT_FALSE(a.directions.empty());
  const WeakDirection& weakest = a.directions[0];
  EXPECT_EQ(weakest.status, DirectionStatus::kUndetermined) << weakest.eigenvalue_ratio;
  EXPECT_NE(weakest.combination.find("T1"), std::string::npos) << weakest.combination;
  EXPECT_NE(weakest.combination.find("T2"), std::string::npos) << weakest.combination;
  EXPECT_NEAR(std::abs(weakest.coefficients[0]), 1.0, 1e-6);
  EXPECT_NEAR(weakest.coefficients[0], -weakest.coefficients[1], 1e-6);
  EXPECT_TRUE(std::isnan(a.std_errors[0]) && std::isnan(a.std_errors[1]));
}

}  // namespace local_analysis_test
}  // namespace vesselid

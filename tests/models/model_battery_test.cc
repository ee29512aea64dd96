// The battery every model variant passes (model_factory.h lists them): the Jet Jacobian of
// the whole-experiment residual against central finite differences, RK4's fourth order of
// convergence, and simulate -> identify recovery from a perturbed start with noise, checked
// against the reported standard errors.
#include <algorithm>
#include <cmath>

#include "gtest/gtest.h"
#include "tests/models/model_factory.h"
#include "tests/support/jacobian_check.h"

namespace vesselid::testing {
namespace model_battery_test {

class ModelBattery : public ::testing::TestWithParam<ModelVariant> {
 protected:
  const ModelVariant& variant() const { return GetParam(); }
  std::unique_ptr<ModelHandle> model_ = GetParam().make();
};

TEST_P(ModelBattery, JetJacobianMatchesFiniteDifferences) {
  const JacobianCase c = variant().jacobian(*model_, variant().truth);
  ASSERT_EQ(c.theta.size(), variant().truth.size() + model_->info().states.size());
  std::unique_ptr<ceres::CostFunction> cost(
      model_->NewExperimentCost(&c.experiment, c.scales, nullptr));
  EXPECT_GE(ExpectJacobianMatchesFiniteDifferences(*cost, c.theta, c.tolerance), c.min_columns);
}

TEST_P(ModelBattery, Rk4ConvergesWithFourthOrder) {
  const Rk4Case c = variant().rk4(*model_);
  auto simulate = [&](double step) {
    const Experiment e = c.build(step);
    std::vector<double> outputs;
    EXPECT_TRUE(
        model_->SimulateOutputs(e, variant().truth.data(), e.initial_state.data(), &outputs));
    return outputs;
  };
  const std::vector<double> reference = simulate(c.reference_step);
  auto max_error = [&](double step) {
    const std::vector<double> y = simulate(step);
    EXPECT_EQ(y.size(), reference.size());
    double error = 0.0;
    for (size_t k = 0; k < y.size(); ++k) error = std::max(error, std::abs(y[k] - reference[k]));
    return error;
  };
  const double e1 = max_error(c.steps[0]), e2 = max_error(c.steps[1]), e3 = max_error(c.steps[2]);
  EXPECT_NEAR(std::log2(e1 / e2), 4.0, c.tolerance) << e1 << " " << e2;
  EXPECT_NEAR(std::log2(e2 / e3), 4.0, c.tolerance) << e2 << " " << e3;
}

TEST_P(ModelBattery, RecoversTruthWithinReportedUncertainty) {
  const std::vector<double>& truth = variant().truth;
  RecoveryCase c = variant().recovery(*model_, truth);
  std::string error;
  auto problem = OutputErrorProblem::Create(model_.get(), std::move(c.experiments), c.specs,
                                            c.options, &error);
  ASSERT_NE(problem, nullptr) << error;
  StageSummary summary;
  ASSERT_TRUE(RunStage(StageOptions(), problem.get(), &summary)) << summary.message;
  ASSERT_TRUE(summary.uncertainty.available) << summary.uncertainty.message;
  int estimated = 0;
  const std::vector<Variable>& variables = problem->variables();
  for (size_t i = 0; i < variables.size(); ++i) {
    const Variable& v = variables[i];
    if (!v.free || v.kind != Variable::Kind::kParameter) continue;
    ++estimated;
    const double t = truth[model_->info().ParameterIndex(v.name)];
    const double sigma = summary.uncertainty.StdError(static_cast<int>(i));
    EXPECT_LT(std::abs(v.value() - t), c.sigmas * sigma)
        << v.name << " = " << v.value() << " +- " << sigma << ", truth " << t;
    if (c.max_relative_std_error > 0.0) {
      EXPECT_LT(sigma, c.max_relative_std_error * std::max(std::abs(t), 0.01)) << v.name;
    }
  }
  EXPECT_EQ(estimated, c.free_parameters);
  if (c.residual_sd > 0.0) {
    EXPECT_NEAR(std::sqrt(summary.uncertainty.residual_variance / c.residual_weight), c.residual_sd,
                c.residual_tolerance * c.residual_sd);
  }
}

INSTANTIATE_TEST_SUITE_P(EveryModel, ModelBattery, ::testing::ValuesIn(ModelVariants()),
                         [](const ::testing::TestParamInfo<ModelVariant>& info) {
                           return info.param.name;
                         });

}  // namespace model_battery_test
}  // namespace vesselid::testing

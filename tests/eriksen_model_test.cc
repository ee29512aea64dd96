// The model battery for the Eriksen-Breivik 2-DOF model: Jet Jacobian of the whole-experiment
// residual against finite differences (all 66 parameters and 5 initial states), RK4 order of
// convergence, and simulate -> identify recovery from a perturbed start with noise, checked
// against the reported standard errors. Plus the basis helpers it is built on.
#include <cmath>
#include <random>

#include "engine/solve/local_solve.h"
#include "engine/solve/output_error_problem.h"
#include "engine/model/polynomial_basis.h"
#include "engine/solve/stage.h"
#include "gtest/gtest.h"
#include "problems/eriksen2dof/handle.h"
#include "tests/eriksen_data.h"
#include "tests/jacobian_check.h"

namespace vesselid {
namespace {

using testing::Level;

ExperimentSpec Spec(std::vector<std::string> outputs) {
  ExperimentSpec spec;
  spec.name = "run";
  spec.inputs = {{"tau_m", "throttle"}, {"tau_delta", "rudder"}};
  const std::map<std::string, std::string> columns = {
      {"N", "n"}, {"E", "e"}, {"chi", "course"}, {"U", "sog"}, {"r", "rot"}};
  for (const std::string& o : outputs) spec.outputs[o] = columns.at(o);
  spec.default_interpolation = Interpolation::kZeroOrderHold;
  return spec;
}

class EriksenModel : public ::testing::Test {
 protected:
  std::unique_ptr<ModelHandle> model_ = eriksen2dof::MakeHandle(eriksen2dof::Model());
  std::vector<double> truth_ = testing::ReferenceCraft(model_->info());
};

TEST(PolynomialBasis, OrderAndNames) {
  double phi[15];
  Monomials(4, 2.0, 3.0, phi);
  const std::vector<std::string> names = MonomialNames(4, "U", "r");
  const double expected[15] = {1, 2, 3, 4, 6, 9, 8, 12, 18, 27, 16, 24, 36, 54, 81};
  ASSERT_EQ(names.size(), 15u);
  for (int k = 0; k < 15; ++k) EXPECT_EQ(phi[k], expected[k]) << names[k];
  EXPECT_EQ(names[7], "U2r");
  EXPECT_EQ(names[12], "U2r2");
  EXPECT_EQ(MonomialPowerOfB(4, 12), 2);
  EXPECT_EQ(MonomialPowerOfB(4, 14), 4);
}

TEST_F(EriksenModel, JetJacobianMatchesFiniteDifferences) {
  const Trajectory data = testing::SimulateRuns(
      *model_, truth_, {{{20, 0.3, 0.2}, {20, 0.5, 0.6}, {20, 0.2, -0.4}}}, 0.5, 0.0, 0.0, 1);
  Experiment e;
  std::string error;
  ASSERT_TRUE(BuildExperiment(Spec({"N", "E", "chi", "U", "r"}), data, model_->info(),
                              ExperimentOptions(), &e, &error))
      << error;
  const int np = static_cast<int>(truth_.size());
  const int nx = 5;
  std::vector<double> scales(np, 1.0);
  scales[1] = 2.0;  // a non-unit scale is part of what is checked
  std::unique_ptr<ceres::CostFunction> cost(model_->NewExperimentCost(&e, scales, nullptr));
  std::vector<double> theta(np + nx);
  // Away from the truth; zero coefficients get small values so that every one matters
  // (the m_r asymptote too).
  for (int i = 0; i < np; ++i) theta[i] = (truth_[i] * 1.05 + (truth_[i] == 0 ? 0.003 : 0)) / scales[i];
  theta[model_->info().ParameterIndex("m_r.tanh")] = 0.3;
  const double x0[5] = {1.0, -2.0, 0.3, 6.0, 0.1};
  for (int i = 0; i < nx; ++i) theta[np + i] = x0[i];
  EXPECT_EQ(testing::ExpectJacobianMatchesFiniteDifferences(*cost, theta, 1e-5), np + nx);
}

TEST_F(EriksenModel, Rk4ConvergesWithFourthOrder) {
  const Trajectory data =
      testing::SimulateRuns(*model_, truth_, {{{40, 0.4, 0.5}}}, 0.8, 0.0, 0.0, 1);
  ExperimentSpec spec = Spec({"E", "U", "r"});
  spec.initial_state = {{"U", 2.0}, {"r", -0.2}, {"chi", 0.0}, {"N", 0.0}, {"E", 0.0}};
  auto simulate = [&](double step) {
    ExperimentOptions options;
    options.max_step = step;
    Experiment e;
    std::string error;
    EXPECT_TRUE(BuildExperiment(spec, data, model_->info(), options, &e, &error)) << error;
    std::vector<double> outputs;
    EXPECT_TRUE(model_->SimulateOutputs(e, truth_.data(), e.initial_state.data(), &outputs));
    return outputs;
  };
  const std::vector<double> reference = simulate(0.8 / 256);
  auto max_error = [&](double step) {
    const std::vector<double> y = simulate(step);
    double error = 0.0;
    for (size_t k = 0; k < y.size(); ++k) error = std::max(error, std::abs(y[k] - reference[k]));
    return error;
  };
  const double e1 = max_error(0.4), e2 = max_error(0.2), e3 = max_error(0.1);
  EXPECT_NEAR(std::log2(e1 / e2), 4.0, 0.4);
  EXPECT_NEAR(std::log2(e2 / e3), 4.0, 0.4);
}

TEST_F(EriksenModel, InadmissibleInertiaFailsTheSimulation) {
  std::vector<double> p = truth_;
  p[model_->info().ParameterIndex("m_U.1")] = -0.5;
  const double x[5] = {0, 0, 0, 3.0, 0.1}, u[2] = {0.3, 0.2};
  double xdot[5];
  EXPECT_FALSE(model_->Derivative(x, u, p.data(), xdot));
  EXPECT_TRUE(model_->Derivative(x, u, truth_.data(), xdot));
}

TEST_F(EriksenModel, RecoversTruthWithinReportedUncertainty) {
  // Random simultaneous steps of both inputs over the envelope, 0.05 m/s and 0.2 deg/s noise.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> throttle(0.05, 0.6), rudder(-1.0, 1.0),
      hold(8.0, 30.0);
  std::vector<Level> levels;
  for (int k = 0; k < 60; ++k) levels.push_back({hold(random), throttle(random), rudder(random)});
  const double rot_noise = 0.2 * M_PI / 180.0;
  const Trajectory data =
      testing::SimulateRuns(*model_, truth_, {levels}, 0.2, 0.05, rot_noise, 5);
  Experiment e;
  std::string error;
  ASSERT_TRUE(BuildExperiment(Spec({"U", "r"}), data, model_->info(), ExperimentOptions(), &e,
                              &error))
      << error;
  const ModelInfo& info = model_->info();
  std::vector<ParameterSpec> specs;
  std::vector<int> free;
  for (size_t i = 0; i < truth_.size(); ++i) {
    ParameterSpec s;
    s.name = info.parameters[i];
    s.start = truth_[i];
    s.role = ParameterRole::kFixed;
    const bool coefficient = s.name.find(".a") == std::string::npos &&
                             s.name.find(".b") == std::string::npos;
    if (coefficient && truth_[i] != 0.0) {
      s.role = ParameterRole::kFree;
      s.start = truth_[i] * (free.size() % 2 == 0 ? 1.2 : 0.85);
      free.push_back(static_cast<int>(i));
    }
    specs.push_back(s);
  }
  ASSERT_EQ(free.size(), 12u);
  // Weights 1/sigma per channel, so that the residual variance is 1.
  e = Experiment();
  ExperimentSpec spec = Spec({"U", "r"});
  spec.output_weights = {{"U", 1.0 / 0.05}, {"r", 1.0 / rot_noise}};
  ASSERT_TRUE(BuildExperiment(spec, data, info, ExperimentOptions(), &e, &error)) << error;
  auto problem = OutputErrorProblem::Create(model_.get(), {e}, specs, OutputErrorOptions(), &error);
  ASSERT_NE(problem, nullptr) << error;
  StageOptions options;
  StageSummary summary;
  ASSERT_TRUE(RunStage(options, problem.get(), &summary)) << summary.message;
  ASSERT_TRUE(summary.uncertainty.available) << summary.uncertainty.message;
  int index = 0;
  const std::vector<Variable>& variables = problem->variables();
  for (size_t i = 0; i < variables.size(); ++i) {
    const Variable& v = variables[i];
    if (!v.free) continue;
    const double sigma = summary.uncertainty.StdError(static_cast<int>(i));
    const double t = truth_[info.ParameterIndex(v.name)];
    EXPECT_LT(std::abs(v.value() - t), 3.0 * sigma) << v.name << " = " << v.value() << " +- " << sigma;
    EXPECT_LT(sigma, 0.2 * std::abs(t)) << v.name;
    ++index;
  }
  EXPECT_EQ(index, 12);
  // Unit-weighted residuals: the residual variance estimates 1 (times the length weight).
  const double length = 1.0 / e.num_samples();
  EXPECT_NEAR(summary.uncertainty.residual_variance / length, 1.0, 0.1);
}

}  // namespace
}  // namespace vesselid

// The battery every Nomoto-family model passes: Jet Jacobian of the whole-experiment residual
// against central finite differences, RK4 order of convergence, and simulate -> identify
// recovery from a perturbed start with heading noise, checked against the reported
// standard errors.
#include <cmath>
#include <random>

#include "engine/solve/covariance.h"
#include "engine/solve/local_solve.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"
#include "gtest/gtest.h"
#include "tests/jacobian_check.h"
#include "tests/nomoto_data.h"

namespace vesselid {
namespace {

using testing::MakeExperiment;

struct FirstOrderCase {
  using Model = nomoto::FirstOrder;
  static std::vector<double> Truth() { return {2.0, -0.17, 0.01}; }
};
struct SecondOrderCase {
  using Model = nomoto::SecondOrder;
  static std::vector<double> Truth() { return {2.0875, 0.3179, 0.1830, -0.1724, 0.01}; }
};
struct NorrbinCase {
  using Model = nomoto::Norrbin;
  static std::vector<double> Truth() { return {2.0, -0.17, 40.0, 0.01}; }
};

// A multi-sine heading loop of the patrol vessel's steering gear and controller.
nomoto::ClosedLoopOptions Loop(double duration, double heading_noise_deg) {
  nomoto::ClosedLoopOptions loop;
  loop.steering_time_constant = 1.0;
  loop.controller_gain = 0.7;
  loop.duration = duration;
  loop.excitation.type = nomoto::Excitation::Type::kMultisine;
  loop.excitation.amplitude = 25.0 * M_PI / 180.0;
  loop.excitation.periods = {60.0, 23.0, 11.0, 5.0, 2.3};
  loop.heading_noise = heading_noise_deg * M_PI / 180.0;
  loop.seed = 7;
  return loop;
}

template <class Case>
class ModelBattery : public ::testing::Test {
 protected:
  std::unique_ptr<ModelHandle> model_ = MakeModelHandle(typename Case::Model());
};

using Cases = ::testing::Types<FirstOrderCase, SecondOrderCase, NorrbinCase>;
TYPED_TEST_SUITE(ModelBattery, Cases);

TYPED_TEST(ModelBattery, JetJacobianMatchesFiniteDifferences) {
  const std::vector<double> truth = TypeParam::Truth();
  Experiment e = MakeExperiment(*this->model_, truth, Loop(60.0, 0.0));
  const int np = static_cast<int>(truth.size());
  const int nx = static_cast<int>(this->model_->info().states.size());
  std::vector<double> scales(np, 1.0);
  scales[0] = 2.0;  // a non-unit scale is part of what is checked
  std::unique_ptr<ceres::CostFunction> cost(this->model_->NewExperimentCost(&e, scales, nullptr));

  // Evaluate away from the optimum, with a non-zero initial state.
  std::vector<double> theta(np + nx);
  for (int i = 0; i < np; ++i) theta[i] = truth[i] * 1.1 / scales[i] + (truth[i] == 0 ? 0.01 : 0);
  for (int i = 0; i < nx; ++i) theta[np + i] = 0.01 * (i + 1);
  // Every parameter and initial state affects the heading.
  EXPECT_EQ(testing::ExpectJacobianMatchesFiniteDifferences(*cost, theta, 1e-6), np + nx);
}

TYPED_TEST(ModelBattery, Rk4ConvergesWithFourthOrder) {
  const std::vector<double> truth = TypeParam::Truth();
  // Heading sampled every 0.8 s; constant rudder after the start so inputs are exact.
  Trajectory data;
  data.source = "step";
  data.names = {"delta", "psi"};
  data.columns.resize(2);
  for (int k = 0; k <= 50; ++k) {
    data.t.push_back(0.8 * k);
    data.columns[0].push_back(0.2);
    data.columns[1].push_back(0.0);
  }
  ExperimentSpec spec;
  spec.name = "step";
  spec.inputs = {{"delta", "delta"}};
  spec.outputs = {{"psi", "psi"}};
  spec.initial_state = {{this->model_->info().states[1], 0.05}};
  auto heading = [&](double step) {
    ExperimentOptions options;
    options.max_step = step;
    Experiment e;
    std::string error;
    EXPECT_TRUE(BuildExperiment(spec, data, this->model_->info(), options, &e, &error)) << error;
    std::vector<double> outputs;
    EXPECT_TRUE(this->model_->SimulateOutputs(e, truth.data(), e.initial_state.data(), &outputs));
    std::vector<double> psi;
    for (int k = 0; k < e.num_nodes(); ++k) psi.push_back(outputs[k * 2]);
    return psi;
  };
  const std::vector<double> reference = heading(0.8 / 512);
  auto max_error = [&](double step) {
    std::vector<double> psi = heading(step);
    double error = 0.0;
    for (size_t k = 0; k < psi.size(); ++k)
      error = std::max(error, std::abs(psi[k] - reference[k]));
    return error;
  };
  const double e1 = max_error(0.1), e2 = max_error(0.05), e3 = max_error(0.025);
  EXPECT_NEAR(std::log2(e1 / e2), 4.0, 0.35);
  EXPECT_NEAR(std::log2(e2 / e3), 4.0, 0.35);
}

TYPED_TEST(ModelBattery, RecoversTruthWithinReportedUncertainty) {
  const std::vector<double> truth = TypeParam::Truth();
  Experiment e = MakeExperiment(*this->model_, truth, Loop(600.0, 0.1));
  const ModelInfo& info = this->model_->info();
  std::vector<ParameterSpec> specs;
  for (size_t i = 0; i < truth.size(); ++i) {
    ParameterSpec s;
    s.name = info.parameters[i];
    // Perturbed start: +30 % / -30 % alternately; the bias starts at zero.
    s.start = info.parameters[i] == "delta_0" ? 0.0 : truth[i] * (i % 2 == 0 ? 1.3 : 0.7);
    s.scale = info.parameters[i] == "delta_0" ? 0.01 : 0.0;
    specs.push_back(s);
  }
  std::string error;
  // The first heading sample is noisy: the initial heading is estimated with the rest.
  OutputErrorOptions problem_options;
  problem_options.free_initial_states = {"psi"};
  auto problem =
      OutputErrorProblem::Create(this->model_.get(), {e}, specs, problem_options, &error);
  ASSERT_NE(problem, nullptr) << error;
  StageOptions options;
  StageSummary summary;
  ASSERT_TRUE(RunStage(options, problem.get(), &summary)) << summary.message;
  ASSERT_TRUE(summary.uncertainty.available) << summary.uncertainty.message;
  for (size_t i = 0; i < truth.size(); ++i) {
    const double sigma = summary.uncertainty.StdError(static_cast<int>(i));
    const double value = problem->variables()[i].value();
    EXPECT_LT(std::abs(value - truth[i]), 3.0 * sigma)
        << info.parameters[i] << " = " << value << " +- " << sigma << ", truth " << truth[i];
    EXPECT_LT(sigma, 0.1 * std::max(std::abs(truth[i]), 0.01)) << info.parameters[i];
  }
  // The residual variance estimates the heading noise variance (0.1 deg).
  const double noise = 0.1 * M_PI / 180.0;
  const double weight2 = 1.0 / e.num_samples();
  EXPECT_NEAR(std::sqrt(summary.uncertainty.residual_variance / weight2), noise, 0.05 * noise);
}

}  // namespace
}  // namespace vesselid

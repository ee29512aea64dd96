// Errors in the input (engine/model/input_noise.h): the cost's Jet derivatives with respect
// to the input corrections match finite differences, and on a patrol-vessel multi-sine with
// a noisy logged rudder (closed loop with a rate-limited steering gear, so that the rudder is
// no spline) the latent input brings the fast time constants T2, T3 closer to the truth.
#include <cmath>
#include <memory>

#include "engine/model/experiment.h"
#include "engine/run/input_noise_notes.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"
#include "gtest/gtest.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace input_correction_test {

nomoto::ClosedLoopOptions PatrolMultisine(double duration, double rudder_noise_deg,
                                          unsigned seed) {
  nomoto::ClosedLoopOptions loop = testing::PatrolVessel().loop;
  loop.duration = duration;
  loop.excitation.type = nomoto::Excitation::Type::kMultisine;
  loop.excitation.periods = {60, 30, 15, 7.5, 4, 2};
  loop.rudder_rate = 10.0 * M_PI / 180;  // a steering gear rate limit the model lacks
  loop.rudder_noise = rudder_noise_deg * M_PI / 180;
  loop.heading_noise = 0.1 * M_PI / 180;
  loop.seed = seed;
  return loop;
}

Experiment Build(const ModelHandle& model, const nomoto::ClosedLoopOptions& loop, bool noisy) {
  Trajectory trajectory;
  std::string error;
  EXPECT_TRUE(nomoto::SimulateClosedLoop(model, testing::PatrolVessel().truth, loop, &trajectory,
                                         &error))
      << error;
  trajectory.source = "patrol";
  ExperimentSpec spec;
  spec.name = "multisine";
  spec.inputs = {{"delta", "delta"}};
  spec.outputs = {{"psi", "psi"}};
  spec.default_interpolation = Interpolation::kCubic;
  if (noisy) spec.input_noise["delta"] = InputNoiseSpec();
  Experiment e;
  EXPECT_TRUE(BuildExperiment(spec, trajectory, model.info(), ExperimentOptions(), &e, &error))
      << error;
  return e;
}

TEST(InputCorrection, JetDerivativesMatchFiniteDifferences) {
  auto model = nomoto::MakeSecondOrderHandle();
  const Experiment e = Build(*model, PatrolMultisine(60.0, 0.5, 3), true);
  ASSERT_EQ(e.input_corrections.size(), 1u);
  const InputCorrectionGrid& grid = e.input_corrections[0];
  EXPECT_EQ(grid.count, 32);
  EXPECT_NEAR(grid.spacing, 60.0 / 32, 1e-9);
  ASSERT_EQ(e.latent_inputs.size(), 1u);
  EXPECT_NEAR(e.latent_inputs[0].sigma, 0.5 * M_PI / 180, 0.1 * 0.5 * M_PI / 180);

  const std::vector<double> truth = testing::PatrolVessel().truth;
  std::unique_ptr<ceres::CostFunction> cost(
      model->NewExperimentCost(&e, std::vector<double>(truth.size(), 1.0), nullptr));
  const int blocks = static_cast<int>(cost->parameter_block_sizes().size());
  ASSERT_EQ(blocks, 5 + 3 + 32);
  std::vector<double> values(truth);
  for (double x : e.initial_state) values.push_back(x);
  for (int j = 0; j < grid.count; ++j) values.push_back(0.7 * std::sin(j));  // c_j / sigma_c
  std::vector<const double*> parameters;
  for (double& v : values) parameters.push_back(&v);
  const int m = cost->num_residuals();
  std::vector<double> r(m), jet(static_cast<size_t>(m) * blocks);
  std::vector<double*> jacobians;
  for (int b = 0; b < blocks; ++b) jacobians.push_back(jet.data() + static_cast<size_t>(b) * m);
  ASSERT_TRUE(cost->Evaluate(parameters.data(), r.data(), jacobians.data()));
  std::vector<double> plus(m), minus(m);
  // 40 directions take two passes of 20 (experiment_cost.h): blocks 0-19 and 20-39.
  for (int b : {3, 8, 9, 19, 20, 39}) {  // K, corrections, both sides of the passes' border
    const double h = 1e-4, saved = values[b];
    values[b] = saved + h;
    ASSERT_TRUE(cost->Evaluate(parameters.data(), plus.data(), nullptr));
    values[b] = saved - h;
    ASSERT_TRUE(cost->Evaluate(parameters.data(), minus.data(), nullptr));
    values[b] = saved;
    double norm = 0.0, diff = 0.0;
    for (int i = 0; i < m; ++i) {
      const double fd = (plus[i] - minus[i]) / (2 * h);
      norm += fd * fd;
      diff += (fd - jet[static_cast<size_t>(b) * m + i]) * (fd - jet[static_cast<size_t>(b) * m + i]);
    }
    EXPECT_GT(norm, 0.0) << "block " << b;
    EXPECT_LT(std::sqrt(diff), 1e-6 * std::sqrt(norm)) << "block " << b;
  }

  // Blocks held constant carry no direction: with every third block's Jacobian left out the
  // others' (now 26 directions, one pass) are the same numbers.
  std::vector<double> some(static_cast<size_t>(m) * blocks, 0.0), r2(m);
  for (int b = 0; b < blocks; ++b) {
    jacobians[b] = b % 3 == 0 ? nullptr : some.data() + static_cast<size_t>(b) * m;
  }
  ASSERT_TRUE(cost->Evaluate(parameters.data(), r2.data(), jacobians.data()));
  for (int b = 0; b < blocks; ++b) {
    if (b % 3 == 0) continue;
    for (int i = 0; i < m; ++i) {
      const double full = jet[static_cast<size_t>(b) * m + i];
      ASSERT_NEAR(some[static_cast<size_t>(b) * m + i], full, 1e-12 * (1.0 + std::abs(full)))
          << "block " << b << " sample " << i;
    }
  }
}

// |relative error| of T2 plus that of T3 after a stage from 20 % off (near enough for the
// local solve to find the minimum with either input).
double FastError(const ModelHandle& model, Experiment e) {
  const std::vector<double> truth = testing::PatrolVessel().truth;
  OutputErrorOptions options;
  options.free_initial_states = {"psi"};
  std::vector<ParameterSpec> specs = testing::FiftyPercentOff(truth);
  const double factor[] = {1.2, 1.0 / 1.2, 1.2, 1.0 / 1.2};
  for (int i = 0; i < 4; ++i) specs[i].start = truth[i] * factor[i];
  std::string error;
  auto problem =
      OutputErrorProblem::Create(&model, {std::move(e)}, specs, options, &error);
  EXPECT_NE(problem, nullptr) << error;
  if (problem == nullptr) return NAN;
  StageOptions stage;
  stage.use_global_start = false;
  StageSummary summary;
  EXPECT_TRUE(RunStage(stage, problem.get(), &summary)) << summary.message;
  const std::vector<double> p = problem->ParametersOf(0);
  std::printf("  T1 %.4f T2 %.4f T3 %.4f K %.5f\n", p[0], p[1], p[2], p[3]);
  return std::abs(p[1] / truth[1] - 1.0) + std::abs(p[2] / truth[2] - 1.0);
}

TEST(InputCorrection, NoisyRudderBiasesFastTimeConstantsLess) {
  auto model = nomoto::MakeSecondOrderHandle();
  double without = 0.0, with = 0.0;
  for (unsigned seed : {21u, 22u, 23u}) {
    const nomoto::ClosedLoopOptions loop = PatrolMultisine(300.0, 0.5, seed);
    const double a = FastError(*model, Build(*model, loop, false));
    const double b = FastError(*model, Build(*model, loop, true));
    without += a;
    with += b;
    std::printf("seed %u: |dT2/T2| + |dT3/T3| = %.4f measured input, %.4f latent input\n", seed,
                a, b);
  }
  EXPECT_LT(with, 0.6 * without);
}

// A stage with a latent input says that its intervals hold the spline as exact (a warning,
// a narrow_intervals finding) and names the parametric bootstrap with the input's noise SD; a stage
// without one says nothing of the kind.
TEST(InputCorrection, IntervalWarningNamesTheBootstrap) {
  auto model = nomoto::MakeSecondOrderHandle();
  const nomoto::ClosedLoopOptions loop = PatrolMultisine(120.0, 0.5, 21u);
  for (bool noisy : {false, true}) {
    std::string error;
    auto problem = OutputErrorProblem::Create(model.get(), {Build(*model, loop, noisy)},
                                              testing::FiftyPercentOff(testing::PatrolVessel().truth),
                                              OutputErrorOptions(), &error);
    ASSERT_NE(problem, nullptr) << error;
    std::vector<std::string> notes;
    std::vector<Finding> findings;
    InputNoiseNotes(*problem, &notes, &findings);
    ASSERT_EQ(findings.size(), noisy ? 1u : 0u);
    if (!noisy) continue;
    EXPECT_EQ(findings[0].kind, FindingKind::kNarrowIntervals);
    EXPECT_EQ(findings[0].severity, FindingSeverity::kWarning);
    EXPECT_NE(findings[0].message.find("truth: estimate, noise: {delta: 0.00"), std::string::npos)
        << findings[0].message;
  }
}

}  // namespace input_correction_test
}  // namespace vesselid

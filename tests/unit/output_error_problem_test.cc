// Structure of output-error problems: several experiments sharing parameters, parameters
// declared per experiment, multi-rate outputs, robust losses and the NLopt global start.
#include "engine/solve/output_error_problem.h"

#include <cmath>

#include "engine/solve/stage.h"
#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace output_error_problem_test {

using testing::ShortLoop;

ParameterSpec Spec(const std::string& name, double start, double lower, double upper,
                   ParameterRole role = ParameterRole::kFree) {
  ParameterSpec s;
  s.name = name;
  s.start = start;
  s.lower = lower;
  s.upper = upper;
  s.role = role;
  return s;
}

double ValueOf(const OutputErrorProblem& p, const std::string& name) {
  for (const Variable& v : p.variables()) {
    if (v.name == name) return v.value();
  }
  ADD_FAILURE() << "no variable " << name;
  return NAN;
}

TEST(OutputErrorProblem, PerExperimentBiasWithSharedDynamics) {
  auto model = nomoto::MakeFirstOrderHandle();
  std::vector<Experiment> runs = {
      testing::MakeExperiment(*model, {2.0, -0.17, 0.02}, ShortLoop(20, 1), Interpolation::kCubic,
                              "a"),
      testing::MakeExperiment(*model, {2.0, -0.17, -0.01}, ShortLoop(13, 2), Interpolation::kCubic,
                              "b")};
  std::string error;
  auto problem =
      OutputErrorProblem::Create(model.get(), runs,
                                 {Spec("T", 3.0, 0.1, 20), Spec("K", -0.1, -1, -0.001),
                                  Spec("delta_0", 0.0, -0.1, 0.1, ParameterRole::kPerExperiment)},
                                 {}, &error);
  ASSERT_NE(problem, nullptr) << error;
  EXPECT_EQ(problem->num_free(), 4);  // T, K, delta_0[a], delta_0[b]
  StageSummary summary;
  ASSERT_TRUE(RunStage(StageOptions(), problem.get(), &summary)) << summary.message;
  EXPECT_NEAR(ValueOf(*problem, "T"), 2.0, 1e-6);
  EXPECT_NEAR(ValueOf(*problem, "K"), -0.17, 1e-7);
  EXPECT_NEAR(ValueOf(*problem, "delta_0[a]"), 0.02, 1e-7);
  EXPECT_NEAR(ValueOf(*problem, "delta_0[b]"), -0.01, 1e-7);
  EXPECT_EQ(summary.fits.size(), 2u);
}

TEST(OutputErrorProblem, MultiRateOutputsComparedOnlyWhereSampled) {
  auto model = nomoto::MakeFirstOrderHandle();
  Trajectory data;
  std::string error;
  ASSERT_TRUE(
      nomoto::SimulateClosedLoop(*model, {2.0, -0.17, 0.0}, ShortLoop(20, 1), &data, &error));
  // Heading at 4 Hz, yaw rate at 20 Hz with a gap.
  const int psi = data.Find("psi"), r = data.Find("r");
  for (size_t k = 0; k < data.t.size(); ++k) {
    if (k % 5 != 0) data.columns[psi][k] = NAN;
    if (data.t[k] > 50 && data.t[k] < 60) data.columns[r][k] = NAN;
  }
  ExperimentSpec spec;
  spec.name = "multirate";
  spec.inputs = {{"delta", "delta"}};
  spec.outputs = {{"psi", "psi"}, {"r", "r"}};
  spec.default_interpolation = Interpolation::kCubic;
  Experiment e;
  ASSERT_TRUE(BuildExperiment(spec, data, model->info(), ExperimentOptions(), &e, &error)) << error;
  EXPECT_EQ(e.output_sample_count[0], 481);         // psi: every 0.25 s over 120 s
  EXPECT_EQ(e.output_sample_count[1], 2401 - 199);  // r: 50..60 s missing
  auto problem = OutputErrorProblem::Create(
      model.get(), {e}, {Spec("T", 3.0, 0.1, 20), Spec("K", -0.1, -1, -0.001)}, {}, &error);
  ASSERT_NE(problem, nullptr) << error;
  StageSummary summary;
  ASSERT_TRUE(RunStage(StageOptions(), problem.get(), &summary)) << summary.message;
  EXPECT_NEAR(ValueOf(*problem, "T"), 2.0, 1e-5);
  EXPECT_EQ(summary.fits[0].channels.size(), 2u);
}

TEST(OutputErrorProblem, RobustLossResistsHeadingOutliers) {
  auto model = nomoto::MakeFirstOrderHandle();
  nomoto::ClosedLoopOptions loop = ShortLoop(20, 3);
  loop.heading_noise = 0.002;
  Experiment e = testing::MakeExperiment(*model, {2.0, -0.17, 0.0}, loop);
  // Wild points in the first third only, so that no initial-heading offset absorbs them.
  for (int i = 100; i < e.num_samples() / 3; i += 37) e.samples[i].value += 0.5;
  auto identify = [&](const std::string& loss) {
    OutputErrorOptions options;
    options.loss = loss;
    options.free_initial_states = {"psi"};
    options.loss_scale = 3 * 0.002 / std::sqrt(static_cast<double>(e.num_samples()));
    std::string error;
    auto problem = OutputErrorProblem::Create(
        model.get(), {e}, {Spec("T", 3.0, 0.1, 20), Spec("K", -0.1, -1, -0.001)}, options, &error);
    EXPECT_NE(problem, nullptr) << error;
    StageSummary summary;
    EXPECT_TRUE(RunStage(StageOptions(), problem.get(), &summary)) << summary.message;
    return std::abs(ValueOf(*problem, "T") - 2.0);
  };
  const double plain = identify("none");
  const double robust = identify("huber");
  EXPECT_LT(robust, 0.01);
  EXPECT_GT(plain, 5 * robust);
}

TEST(OutputErrorProblem, GlobalStartRefinesBestCandidates) {
  auto model = nomoto::MakeNorrbinHandle();
  Experiment e = testing::MakeExperiment(*model, {2.0, -0.17, 40.0, 0.0}, ShortLoop(20, 4));
  std::string error;
  auto problem = OutputErrorProblem::Create(
      model.get(), {e},
      {Spec("T", 19.0, 0.1, 20), Spec("K", -0.9, -1, -0.001), Spec("alpha", 0.0, 0, 200)}, {},
      &error);
  ASSERT_NE(problem, nullptr) << error;
  StageOptions options;
  options.use_global_start = true;
  options.global.algorithm = "GN_DIRECT_L";
  options.global.max_evaluations = 300;
  options.global.candidates = 2;
  StageSummary summary;
  ASSERT_TRUE(RunStage(options, problem.get(), &summary)) << summary.message;
  EXPECT_EQ(summary.global.variables, (std::vector<std::string>{"T", "K", "alpha"}));
  EXPECT_LE(summary.global.evaluations, 301);
  EXPECT_EQ(summary.refinements.size(), 3u);  // start point + 2 candidates
  EXPECT_NEAR(ValueOf(*problem, "T"), 2.0, 1e-5);
  EXPECT_NEAR(ValueOf(*problem, "alpha"), 40.0, 1e-3);
}

TEST(OutputErrorProblem, RejectsUnknownNamesAndTooManyDirections) {
  auto model = nomoto::MakeFirstOrderHandle();
  Experiment e = testing::MakeExperiment(*model, {2.0, -0.17, 0.0}, ShortLoop(20, 1));
  std::string error;
  EXPECT_EQ(OutputErrorProblem::Create(model.get(), {e}, {Spec("Q", 1, 0, 2)}, {}, &error),
            nullptr);
  EXPECT_NE(error.find("unknown parameter 'Q'"), std::string::npos) << error;
  OutputErrorOptions options;
  options.free_initial_states = {"yaw"};
  EXPECT_EQ(OutputErrorProblem::Create(model.get(), {e}, {}, options, &error), nullptr);
  EXPECT_NE(error.find("unknown state 'yaw'"), std::string::npos) << error;
  options.free_initial_states = {};
  options.loss = "tukey";
  EXPECT_EQ(OutputErrorProblem::Create(model.get(), {e}, {}, options, &error), nullptr);
  EXPECT_NE(error.find("unknown loss 'tukey'"), std::string::npos) << error;
}

}  // namespace output_error_problem_test
}  // namespace vesselid

// The bootstrap covariance methods on seed 003's patrol vessel under a multi-sine heading set
// point, simulated by the closed-loop simulator (steering gear, autopilot on the true rudder),
// not by the identified model, with Gaussian noise on the logged heading (and rudder). Heading
// noise alone leaves white residuals: the block bootstrap agrees with the Hessian; rudder
// noise, integrated by the model (psi' = r), leaves serially correlated residuals the blocks
// keep: its K standard error exceeds the Hessian's. The experiment bootstrap resamples
// independent runs; with fewer than five it is refused and the stage keeps its figures.
#include <cmath>
#include <cstdio>

#include "engine/run/bootstrap_uncertainty.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"
#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace bootstrap_uncertainty_test {

constexpr double kDegree = M_PI / 180.0;
constexpr int kK = 3;  // K, the gain the integrated rudder noise blurs most

// Bootstrap over Hessian standard error per shared parameter, to the test log.
void PrintRatios(const char* what, const Uncertainty& u) {
  std::printf("%s: bootstrap / Hessian SE", what);
  for (size_t i = 0; i < 4 && i < u.hessian_std_errors.size(); ++i) {
    std::printf(" %.3g", u.std_errors[i] / u.hessian_std_errors[i]);
  }
  std::printf(" (T1 T2 T3 K)\n");
}

struct Solved {
  std::unique_ptr<ModelHandle> model;
  std::unique_ptr<OutputErrorProblem> problem;
  OutputErrorOptions problem_options;
  StageOptions options;
  StageSummary summary;
};

// `runs` closed-loop records of `duration` s, seeds 12, 13, ...
std::unique_ptr<Solved> Solve(double rudder_noise_deg, double duration, int records,
                              UncertaintyMethod method, int bootstrap_runs, int threads) {
  auto s = std::make_unique<Solved>();
  s->model = nomoto::MakeSecondOrderHandle();
  testing::SeedVessel vessel = testing::PatrolVessel();
  vessel.loop.duration = duration;
  vessel.loop.excitation.type = nomoto::Excitation::Type::kMultisine;
  vessel.loop.excitation.periods = {60, 30, 15, 7.5, 4, 2};
  vessel.loop.rudder_noise = rudder_noise_deg * kDegree;
  vessel.loop.heading_noise = 0.1 * kDegree;
  std::vector<Experiment> experiments;
  for (int i = 0; i < records; ++i) {
    vessel.loop.seed = 12 + i;
    experiments.push_back(testing::MakeExperiment(*s->model, vessel.truth, vessel.loop));
    experiments.back().name = "run" + std::to_string(i);
  }
  std::vector<ParameterSpec> specs = testing::FiftyPercentOff(vessel.truth);
  for (int i = 0; i < 4; ++i) specs[i].start = vessel.truth[i];
  s->problem_options.free_initial_states = {"psi"};
  std::string error;
  s->problem = OutputErrorProblem::Create(s->model.get(), std::move(experiments), specs,
                                          s->problem_options, &error);
  EXPECT_NE(s->problem, nullptr) << error;
  s->options.name = "multisine";
  s->options.uncertainty.method = method;
  s->options.uncertainty.bootstrap.runs = bootstrap_runs;
  s->options.uncertainty.bootstrap.num_threads = threads;
  EXPECT_TRUE(RunStage(s->options, s->problem.get(), &s->summary)) << s->summary.message;
  BootstrapStageUncertainty(s->options, s->problem_options, s->problem.get(), &s->summary);
  return s;
}

TEST(BootstrapUncertainty, BlocksAgreeWithTheHessianOnWhiteResiduals) {
  const auto s = Solve(0.0, 300.0, 1, UncertaintyMethod::kBlockBootstrap, 40, 0);
  const Uncertainty& u = s->summary.uncertainty;
  ASSERT_TRUE(u.available) << u.message;
  EXPECT_EQ(u.method, "block_bootstrap");
  EXPECT_EQ(u.bootstrap_runs, 40);
  EXPECT_EQ(u.bootstrap_failed, 0);
  EXPECT_GT(u.block_length, 0.0);
  ASSERT_EQ(u.hessian_std_errors.size(), u.std_errors.size());
  PrintRatios("heading noise", u);
  for (int i = 0; i < 4; ++i) {  // T1, T2, T3, K
    EXPECT_NEAR(u.std_errors[i] / u.hessian_std_errors[i], 1.0, 0.35)
        << i << ": " << u.std_errors[i] << " vs " << u.hessian_std_errors[i];
  }
  // The replicates kept (the exported model's ensemble) are the ones the standard errors come
  // from: their sample SD is the reported one.
  ASSERT_EQ(u.replicates.size(), 40u);
  ASSERT_EQ(u.replicate_names.size(), u.variables.size());
  EXPECT_EQ(u.replicate_names[3], "K");
  for (int i = 0; i < 4; ++i) {
    double mean = 0.0, variance = 0.0;
    for (const std::vector<double>& r : u.replicates) mean += r[i] / 40.0;
    for (const std::vector<double>& r : u.replicates)
      variance += (r[i] - mean) * (r[i] - mean) / 39.0;
    EXPECT_NEAR(std::sqrt(variance), u.std_errors[i], 1e-9 * u.std_errors[i]) << i;
  }
}

TEST(BootstrapUncertainty, BlocksKeepTheRudderNoisesCorrelation) {
  const auto s = Solve(0.1, 300.0, 1, UncertaintyMethod::kBlockBootstrap, 40, 0);
  const Uncertainty& u = s->summary.uncertainty;
  ASSERT_TRUE(u.available) << u.message;
  ASSERT_EQ(u.hessian_std_errors.size(), u.std_errors.size());
  PrintRatios("rudder noise", u);
  EXPECT_GT(u.std_errors[kK], kHacRatioLimit * u.hessian_std_errors[kK])
      << u.std_errors[kK] << " vs " << u.hessian_std_errors[kK];
}

TEST(BootstrapUncertainty, ResultDoesNotDependOnTheThreads) {
  const auto one = Solve(0.1, 120.0, 1, UncertaintyMethod::kBlockBootstrap, 10, 1);
  const auto two = Solve(0.1, 120.0, 1, UncertaintyMethod::kBlockBootstrap, 10, 2);
  ASSERT_TRUE(one->summary.uncertainty.available);
  EXPECT_EQ(one->summary.uncertainty.std_errors, two->summary.uncertainty.std_errors);
}

TEST(BootstrapUncertainty, ExperimentsResampledGiveFiniteStandardErrors) {
  const auto s = Solve(0.1, 60.0, 6, UncertaintyMethod::kExperimentBootstrap, 20, 0);
  const Uncertainty& u = s->summary.uncertainty;
  ASSERT_TRUE(u.available) << u.message;
  EXPECT_EQ(u.method, "experiment_bootstrap");
  for (int i = 0; i < 4; ++i) {
    EXPECT_TRUE(std::isfinite(u.std_errors[i]) && u.std_errors[i] > 0.0) << i;
  }
}

TEST(BootstrapUncertainty, FewExperimentsAreRefusedAndTheStageKeepsItsFigures) {
  const auto s = Solve(0.0, 60.0, 2, UncertaintyMethod::kExperimentBootstrap, 10, 0);
  EXPECT_NE(s->summary.uncertainty.method, "experiment_bootstrap");
  EXPECT_TRUE(s->summary.uncertainty.available);
  bool refused = false;
  for (const Finding& f : s->summary.findings) {
    if (f.kind != FindingKind::kBootstrap) continue;
    refused = true;
    EXPECT_EQ(f.severity, FindingSeverity::kWarning);
    const std::string& note = f.message;
    EXPECT_NE(note.find("stage 'multisine' needs at least 5"), std::string::npos) << note;
    EXPECT_NE(note.find("segment_length"), std::string::npos) << note;
  }
  EXPECT_TRUE(refused);
}

}  // namespace bootstrap_uncertainty_test
}  // namespace vesselid

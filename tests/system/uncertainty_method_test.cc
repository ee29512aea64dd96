// The stage's uncertainty methods on seed 003's patrol vessel under a multi-sine heading set
// point, simulated by the closed-loop simulator (steering gear, autopilot on the true rudder)
// with Gaussian noise on the logged rudder and heading. Rudder noise, integrated by the model
// (psi' = r), leaves serially correlated residuals: the HAC standard errors exceed the
// Hessian's and `auto` reports them; heading noise alone leaves white residuals and `auto`
// keeps the Hessian; `hessian` chosen by the user on the noisy rudder says by how much its
// intervals are too narrow.
#include <cmath>

#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"
#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace uncertainty_method_test {

constexpr double kDegree = M_PI / 180.0;

StageSummary Solve(double rudder_noise_deg, UncertaintyMethod method) {
  auto model = nomoto::MakeSecondOrderHandle();
  testing::SeedVessel vessel = testing::PatrolVessel();
  vessel.loop.duration = 300.0;
  vessel.loop.excitation.type = nomoto::Excitation::Type::kMultisine;
  vessel.loop.excitation.periods = {60, 30, 15, 7.5, 4, 2};
  vessel.loop.rudder_noise = rudder_noise_deg * kDegree;
  vessel.loop.heading_noise = 0.1 * kDegree;
  vessel.loop.seed = 12;
  const Experiment e = testing::MakeExperiment(*model, vessel.truth, vessel.loop);
  std::vector<ParameterSpec> specs = testing::FiftyPercentOff(vessel.truth);
  for (int i = 0; i < 4; ++i) specs[i].start = vessel.truth[i];
  OutputErrorOptions problem_options;
  problem_options.free_initial_states = {"psi"};
  std::string error;
  auto problem = OutputErrorProblem::Create(model.get(), {e}, specs, problem_options, &error);
  EXPECT_NE(problem, nullptr) << error;
  StageOptions options;
  options.uncertainty.method = method;
  StageSummary summary;
  EXPECT_TRUE(RunStage(options, problem.get(), &summary)) << summary.message;
  return summary;
}

TEST(UncertaintyMethod, RudderNoiseMakesAutoReportTheHac) {
  const StageSummary s = Solve(0.1, UncertaintyMethod::kAuto);
  const Uncertainty& u = s.uncertainty;
  ASSERT_TRUE(u.available);
  EXPECT_EQ(u.method, "sandwich_hac");
  EXPECT_NE(u.method_reason.find("serially correlated"), std::string::npos) << u.method_reason;
  ASSERT_EQ(u.hessian_std_errors.size(), u.std_errors.size());
  const int k = 3;  // K, the gain the integrated rudder noise blurs most
  EXPECT_GT(u.std_errors[k], kHacRatioLimit * u.hessian_std_errors[k]);
}

TEST(UncertaintyMethod, HeadingNoiseAloneKeepsTheHessian) {
  const StageSummary s = Solve(0.0, UncertaintyMethod::kAuto);
  EXPECT_EQ(s.uncertainty.method, "hessian");
  EXPECT_TRUE(s.uncertainty.hessian_std_errors.empty());
  EXPECT_NE(s.uncertainty.method_reason.find("within"), std::string::npos);
}

TEST(UncertaintyMethod, ChosenHessianWarnsThatItsIntervalsAreTooNarrow) {
  const StageSummary s = Solve(0.1, UncertaintyMethod::kHessian);
  EXPECT_EQ(s.uncertainty.method, "hessian");
  bool warned = false;
  for (const Finding& f : s.findings) {
    if (f.kind != FindingKind::kNarrowIntervals) continue;
    warned = true;
    EXPECT_EQ(f.parameter, "K");
    EXPECT_GT(f.value, f.threshold);
    const std::string& note = f.message;
    EXPECT_NE(note.find("K: Hessian SE"), std::string::npos) << note;
    EXPECT_NE(note.find("narrower than the HAC SE"), std::string::npos) << note;
  }
  EXPECT_TRUE(warned);
}

TEST(UncertaintyMethod, AutoRuleIsTheLargestRatio) {
  EXPECT_EQ(ChooseUncertaintyMethod({{"a", 1.0, 1.4}, {"b", 2.0, 2.9}}), UncertaintyMethod::kHessian);
  EXPECT_EQ(ChooseUncertaintyMethod({{"a", 1.0, 1.4}, {"b", 2.0, 3.1}}),
            UncertaintyMethod::kSandwichHac);
  EXPECT_EQ(ChooseUncertaintyMethod({}), UncertaintyMethod::kHessian);
}

}  // namespace uncertainty_method_test
}  // namespace vesselid

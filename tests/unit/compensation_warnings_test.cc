// Compensating estimates (compensation_warnings.h) and structure hints through the run's
// warnings (run_warnings.h): a pair above |correlation| 0.999 is named with its correlation,
// the one to drop (larger relative standard error) and the model's hint; pairs below it,
// pairs determined to 1 % each, initial states and undetermined pairs are not; a dead zone at its
// bound says what it means.
#include "engine/run/compensation_warnings.h"

#include <cmath>

#include "engine/run/run_warnings.h"
#include "gtest/gtest.h"
#include "problems/input_gain/handles.h"

namespace vesselid {
namespace {

Estimate Parameter(const std::string& name, double value, double std_error) {
  Estimate e;
  e.name = name;
  e.value = value;
  e.std_error = std_error;
  return e;
}

// A quadratic law's fit of a purely quadratic thruster: b_u small, k_f large, correlation -1.
StageResult ThrustStage(double correlation) {
  StageResult stage;
  stage.name = "refinement";
  stage.estimates = {Parameter("u.u", -0.4, 0.01), Parameter("b_u", 0.013, 0.001),
                     Parameter("k_f", 87.0, 50.0)};
  Estimate state = Parameter("u", 0.8, 0.01);
  state.kind = EstimateKind::kInitialState;
  state.experiment = "log@3";
  stage.estimates.push_back(state);
  stage.correlation_names = {"u.u", "b_u", "k_f", "u[log@3]"};
  stage.correlation = Eigen::MatrixXd::Identity(4, 4);
  stage.correlation(1, 2) = stage.correlation(2, 1) = correlation;
  stage.correlation(0, 1) = stage.correlation(1, 0) = 0.3;
  stage.correlation(0, 3) = stage.correlation(3, 0) = 0.9999;  // an initial state: not named
  return stage;
}

TEST(CompensationWarnings, NamesThePairTheOneToDropAndTheModelsHint) {
  const ModelInfo info = input_gain::MakeStaticHandle({})->info();
  std::vector<std::string> warnings;
  AddCompensationWarnings(info, ThrustStage(-0.99996), "stage 'refinement': ", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  const std::string& w = warnings[0];
  EXPECT_EQ(w.rfind("stage 'refinement': b_u and k_f compensate each other (correlation "
                    "-1.0000): the data determine only their combination; drop or fix k_f "
                    "(relative standard error 57.5 %; b_u: relative standard error 7.69 %)",
                    0),
            0u)
      << w;
  EXPECT_NE(w.find("try thrust: [\"n|n|\"] (or fix k_f)"), std::string::npos) << w;

  warnings.clear();
  AddCompensationWarnings(info, ThrustStage(-0.998), "", &warnings);
  EXPECT_TRUE(warnings.empty());
  AddCompensationWarnings(info, ThrustStage(std::nan("")), "", &warnings);
  EXPECT_TRUE(warnings.empty());
  // Determined to better than 1 % each despite the correlation (noise-free data): no warning.
  StageResult determined = ThrustStage(-0.99996);
  determined.estimates[1].std_error = 1e-5;
  determined.estimates[2].std_error = 0.5;
  AddCompensationWarnings(info, determined, "", &warnings);
  EXPECT_TRUE(warnings.empty());
}

TEST(CompensationWarnings, LinkedPairsMakeOneGroup) {
  StageResult stage;
  const int n = 5;  // p0..p3 linked (p0/p1, p1/p2, p2/p3), p4 free of them
  stage.correlation = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    stage.correlation_names.push_back("p" + std::to_string(i));
    stage.estimates.push_back(Parameter("p" + std::to_string(i), 1.0, i == 2 ? 0.5 : 0.1));
  }
  const double link[3] = {0.9995, -0.9999, 0.9993};
  for (int i = 0; i < 3; ++i) stage.correlation(i, i + 1) = stage.correlation(i + 1, i) = link[i];
  stage.correlation(0, 4) = stage.correlation(4, 0) = 0.99;
  std::vector<std::string> warnings;
  AddCompensationWarnings(ModelInfo(), stage, "", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "p0, p1, p2 and p3 compensate each other (3 pairs above |correlation| 0.999, "
            "strongest p1/p2 -0.9999): the data determine only combinations of them; drop or "
            "fix p2 (relative standard error 50 %)");
}

TEST(CompensationWarnings, ReachTheRunsWarningsWithTheDeadZoneNamed) {
  RunConfig config;
  config.model = input_gain::MakeDynamicHandle({});
  RunResult run;
  run.stages.push_back(ThrustStage(0.99992));
  run.stages[0].summary.notes = {
      "d_f is at its upper bound 0.15: the profile search ends there; the data pull it further"};
  AddRunWarnings(config, &run);
  bool compensation = false, dead_zone = false;
  for (const std::string& w : run.warnings) {
    compensation |= w.find("b_u and k_f compensate each other (correlation +0.9999") == 20;
    dead_zone |= w.find("stage 'refinement': d_f is at its upper bound 0.15") == 0 &&
                 w.find("a dead zone at its bound stands in for a thrust law the model lacks") !=
                     std::string::npos;
  }
  EXPECT_TRUE(compensation);
  EXPECT_TRUE(dead_zone);
}

}  // namespace
}  // namespace vesselid

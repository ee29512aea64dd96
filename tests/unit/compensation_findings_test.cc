// Compensating estimates (compensation_findings.h) and structure hints through the run's
// findings (run_findings.h): a pair above |correlation| 0.999 is named with its correlation,
// the one to drop (larger relative standard error) and the model's hint, per-experiment values
// included; pairs below it, pairs determined to 30 % each, initial states and undetermined
// pairs are not; a dead zone at its bound says what it means, and goes when the value moves.
#include "engine/diagnose/compensation_findings.h"

#include <cmath>

#include "engine/diagnose/run_findings.h"
#include "gtest/gtest.h"
#include "problems/input_gain/handles.h"

namespace vesselid {
namespace compensation_findings_test {

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
  stage.estimates = {Parameter("u.u", -0.4, 0.01), Parameter("b_u", 0.013, 0.005),
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

TEST(CompensationFindings, NamesThePairTheOneToDropAndTheModelsHint) {
  const ModelInfo info = input_gain::MakeStaticHandle({})->info();
  std::vector<Finding> findings;
  AddCompensationFindings(info, ThrustStage(-0.99996), &findings);
  ASSERT_EQ(findings.size(), 1u);
  const Finding& f = findings[0];
  EXPECT_EQ(f.kind, FindingKind::kCompensation);
  EXPECT_EQ(f.severity, FindingSeverity::kWarning);
  EXPECT_EQ(f.stage, "refinement");
  EXPECT_EQ(f.parameter, "b_u and k_f");
  EXPECT_NEAR(f.value, -0.99996, 1e-12);
  EXPECT_EQ(f.threshold, kCompensationCorrelation);
  EXPECT_EQ(f.message.rfind("b_u and k_f compensate each other (correlation "
                            "-1.0000): the data determine only their combination; drop or fix "
                            "k_f (relative standard error 57.5 %; b_u: relative standard error "
                            "38.5 %)",
                            0),
            0u)
      << f.message;
  EXPECT_NE(f.message.find("try thrust: [\"n|n|\"] (or fix k_f)"), std::string::npos)
      << f.message;

  findings.clear();
  AddCompensationFindings(info, ThrustStage(-0.998), &findings);
  EXPECT_TRUE(findings.empty());
  AddCompensationFindings(info, ThrustStage(std::nan("")), &findings);
  EXPECT_TRUE(findings.empty());
  // One of them determined (b_u to 7.7 %): its standard error carries the trade-off, and
  // k_f's 57.5 % is weakly_determined's to judge: a note.
  StageResult one = ThrustStage(-0.99996);
  one.estimates[1].std_error = 0.001;
  AddCompensationFindings(info, one, &findings);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].severity, FindingSeverity::kInfo);
  EXPECT_NE(findings[0].message.find("b_u is determined all the same"), std::string::npos)
      << findings[0].message;
  findings.clear();
  // Determined to better than 30 % each despite the correlation (noise-free data): quiet.
  StageResult determined = ThrustStage(-0.99996);
  determined.estimates[1].std_error = 1e-5;
  determined.estimates[2].std_error = 0.5;
  AddCompensationFindings(info, determined, &findings);
  EXPECT_TRUE(findings.empty());
}

// A gain and one run's rudder bias that trade off (a run whose rudder barely moves).
TEST(CompensationFindings, PerExperimentValuesCount) {
  StageResult stage;
  stage.name = "turning";
  stage.estimates = {Parameter("K", 0.05, 0.004), Parameter("delta_0[zz1]", 0.002, 0.003),
                     Parameter("delta_0[zz2]", -0.001, 0.001)};
  stage.estimates[1].role = stage.estimates[2].role = ParameterRole::kPerExperiment;
  stage.estimates[1].experiment = "zz1";
  stage.estimates[2].experiment = "zz2";
  stage.correlation_names = {"K", "delta_0[zz1]", "delta_0[zz2]"};
  stage.correlation = Eigen::MatrixXd::Identity(3, 3);
  stage.correlation(0, 1) = stage.correlation(1, 0) = -0.9999;
  std::vector<Finding> findings;
  AddCompensationFindings(ModelInfo(), stage, &findings);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].parameter, "K and delta_0[zz1]");
  EXPECT_NE(findings[0].message.find("drop or fix delta_0[zz1]"), std::string::npos)
      << findings[0].message;
  // Uncorrelated: quiet.
  stage.correlation(0, 1) = stage.correlation(1, 0) = -0.5;
  findings.clear();
  AddCompensationFindings(ModelInfo(), stage, &findings);
  EXPECT_TRUE(findings.empty());
}

TEST(CompensationFindings, LinkedPairsMakeOneGroup) {
  StageResult stage;
  const int n = 5;  // p0..p3 linked (p0/p1, p1/p2, p2/p3), p4 free of them
  stage.correlation = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    stage.correlation_names.push_back("p" + std::to_string(i));
    stage.estimates.push_back(Parameter("p" + std::to_string(i), 1.0, i == 2 ? 0.9 : 0.6));
  }
  const double link[3] = {0.9995, -0.9999, 0.9993};
  for (int i = 0; i < 3; ++i) stage.correlation(i, i + 1) = stage.correlation(i + 1, i) = link[i];
  stage.correlation(0, 4) = stage.correlation(4, 0) = 0.99;
  std::vector<Finding> findings;
  AddCompensationFindings(ModelInfo(), stage, &findings);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].message,
            "p0, p1, p2 and p3 compensate each other (3 pairs above |correlation| 0.999, "
            "strongest p1/p2 -0.9999): the data determine only combinations of them; drop or "
            "fix p2 (relative standard error 90 %)");
}

TEST(CompensationFindings, ReachTheRunsFindingsWithTheDeadZoneNamed) {
  RunConfig config;
  config.model = input_gain::MakeDynamicHandle({});
  RunResult run;
  run.stages.push_back(ThrustStage(0.99992));
  Estimate dead_zone = Parameter("d_f", 0.15, 0.01);
  dead_zone.lower = 0.0;
  dead_zone.upper = 0.15;
  run.stages[0].estimates.push_back(dead_zone);
  DiagnoseRun(config, &run);
  bool compensation = false, at_bound = false;
  for (const Finding& f : run.stages[0].findings) {
    compensation |= f.kind == FindingKind::kCompensation && f.parameter == "b_u and k_f" &&
                    f.message.rfind("b_u and k_f compensate each other (correlation +0.9999", 0) ==
                        0;
    at_bound |= f.kind == FindingKind::kAtBound && f.parameter == "d_f" && f.threshold == 0.15 &&
                f.message.find("a dead zone at its bound stands in for a thrust law the model "
                               "lacks") != std::string::npos;
  }
  EXPECT_TRUE(compensation);
  EXPECT_TRUE(at_bound);
  EXPECT_EQ(run.stages[0].verdict, Verdict::kDoubtful);
  EXPECT_EQ(run.verdict, Verdict::kDoubtful);
  // A re-solve moves the value off its bound and the pair apart: no finding survives it.
  run.stages[0].estimates.back().value = 0.1;
  run.stages[0].correlation(1, 2) = run.stages[0].correlation(2, 1) = 0.2;
  run.findings.clear();
  DiagnoseRun(config, &run);
  EXPECT_TRUE(run.stages[0].findings.empty());
  EXPECT_EQ(run.stages[0].verdict, Verdict::kGood);
  EXPECT_EQ(run.verdict, Verdict::kGood);
}

}  // namespace compensation_findings_test
}  // namespace vesselid

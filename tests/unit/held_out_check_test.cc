// The held-out guard (CompareHeldOut, held_out.h): a stage is worse than its start when it
// makes more held-out runs diverge or, diverging alike, predicts worse on the runs both
// simulate; but more diverging runs do not set aside a stage whose start is far worse on the
// runs both simulate (the start of a least-squares stage is the config's guess, not a model:
// a held-out position error of 3e5 m at the start against 1 m at the estimate).
#include <string>
#include <vector>

#include "engine/run/held_out.h"
#include "engine/run/parameter_ledger.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace held_out_check_test {

ExperimentFit Fit(const std::string& name, double mae, bool diverged = false) {
  ExperimentFit fit;
  fit.experiment = name;
  fit.diverged = diverged;
  if (!diverged) {
    ChannelMetrics c;
    c.output = "n";
    c.samples = 100;
    c.mae = mae;
    fit.channels.push_back(c);
  }
  return fit;
}

TEST(HeldOutCheck, MoreDivergingRunsAreWorseUnlessTheStartIsFarWorse) {
  // Two runs diverge at the estimate, none at its start, and the start is no better elsewhere
  // than twice the estimate's error: worse.
  HeldOutCheck check = CompareHeldOut({Fit("a", 1.5), Fit("b", 1.5), Fit("c", 1.5)},
                                      {Fit("a", 1.0), Fit("b", 0.0, true), Fit("c", 0.0, true)});
  EXPECT_TRUE(check.worse);
  EXPECT_FALSE(check.start_far_worse);
  EXPECT_EQ(check.stage_diverged, 2);
  // The start's error on the run both simulate is 3e5 times the estimate's: kept.
  check = CompareHeldOut({Fit("a", 3e5), Fit("b", 2e5), Fit("c", 1e5)},
                         {Fit("a", 1.0), Fit("b", 0.0, true), Fit("c", 0.0, true)});
  EXPECT_FALSE(check.worse);
  EXPECT_TRUE(check.start_far_worse);
  ASSERT_EQ(check.outputs.size(), 1u);
  EXPECT_EQ(check.start_mae[0], 3e5);  // pooled over run a only: like with like
  EXPECT_EQ(check.stage_mae[0], 1.0);
}

TEST(HeldOutCheck, TheMaeComparesTheRunsBothSimulate) {
  // Run b diverges at the start only: the estimate's larger error on b does not count.
  HeldOutCheck check = CompareHeldOut({Fit("a", 1.0), Fit("b", 0.0, true)},
                                      {Fit("a", 0.9), Fit("b", 50.0)});
  EXPECT_FALSE(check.worse);
  EXPECT_EQ(check.stage_mae[0], 0.9);
  // Diverging alike, a worse error on the common runs is worse.
  check = CompareHeldOut({Fit("a", 1.0), Fit("b", 1.0)}, {Fit("a", 1.2), Fit("b", 1.0)});
  EXPECT_TRUE(check.worse);
  EXPECT_NEAR(check.stage_mae[0], 1.1, 1e-12);
}

// The guard's baseline: the better of the stage's start and the previous stages' values.
TEST(HeldOutCheck, PredictsBetterComparesDivergingRunsFirstThenTheMae) {
  EXPECT_TRUE(PredictsBetter({Fit("a", 0.9), Fit("b", 1.0)}, {Fit("a", 1.0), Fit("b", 1.0)}));
  EXPECT_FALSE(PredictsBetter({Fit("a", 1.0), Fit("b", 1.0)}, {Fit("a", 1.0), Fit("b", 1.0)}));
  EXPECT_FALSE(PredictsBetter({Fit("a", 0.1), Fit("b", 0.0, true)},
                              {Fit("a", 1.0), Fit("b", 1.0)}));
  EXPECT_TRUE(PredictsBetter({Fit("a", 5.0), Fit("b", 5.0)},
                             {Fit("a", 1.0), Fit("b", 0.0, true)}));
}

// A stage set aside against the previous stages' values leaves the ledger as they left it; one
// set aside against its start enters its start values; a kept one its estimates.
TEST(HeldOutCheck, ASetAsideStageLeavesItsBaselinesValues) {
  StageResult stage;
  stage.name = "refine";
  Estimate t;
  t.name = "T";
  t.kind = EstimateKind::kParameter;
  t.role = ParameterRole::kFree;
  t.value = 9.0;
  t.start = 3.0;
  stage.estimates = {t};
  ParameterLedger ledger;
  ledger.latest["T"] = 5.0;  // the previous stage's
  stage.rejected = "worse";
  stage.held_out.baseline = "previous";
  EXPECT_EQ(stage.held_out.BaselineText(), "the previous stages' values");
  RecordStageOrItsBaseline(stage, &ledger);
  EXPECT_EQ(ledger.latest["T"], 5.0);
  stage.held_out.baseline = "start";
  RecordStageOrItsBaseline(stage, &ledger);
  EXPECT_EQ(ledger.latest["T"], 3.0);
  stage.rejected.clear();
  RecordStageOrItsBaseline(stage, &ledger);
  EXPECT_EQ(ledger.latest["T"], 9.0);
}

}  // namespace held_out_check_test
}  // namespace vesselid

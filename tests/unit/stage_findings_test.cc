// The diagnose layer's rules on hand-made stage results (stage_findings.h, run_findings.h):
// each fires on what it names, with its value and threshold, and a good stage stays quiet.
#include "engine/diagnose/stage_findings.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/diagnose/run_findings.h"
#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"

namespace vesselid {
namespace stage_findings_test {

Estimate Free(const std::string& name, double value, double std_error) {
  Estimate e;
  e.name = name;
  e.value = value;
  e.std_error = std_error;
  e.lower = -10.0;
  e.upper = 10.0;
  return e;
}

ChannelMetrics Channel(double r2, double fit, double mae, double hold_mae) {
  ChannelMetrics m;
  m.experiment = "run";
  m.output = "psi";
  m.samples = 1000;
  m.r2 = r2;
  m.fit_percent = fit;
  m.rmse = 0.1;
  m.mae = mae;
  m.hold_mae = hold_mae;
  m.noise = 0.001;
  return m;
}

// A converged output-error stage with a good fit and determined estimates.
StageResult GoodStage() {
  StageResult stage;
  stage.name = "fit";
  stage.estimates = {Free("T", 2.0, 0.02), Free("K", -0.17, 0.001)};
  LocalSolveSummary local;
  local.run = local.usable = true;
  local.iterations = 12;
  local.successful_steps = 10;
  local.initial_cost = 5.0;
  local.final_cost = 1.0;
  local.termination = "CONVERGENCE";
  stage.summary.usable = true;
  stage.summary.refinements = {local};
  stage.summary.chosen = 0;
  stage.summary.uncertainty.available = true;
  ExperimentFit fit;
  fit.experiment = "run";
  fit.channels = {Channel(0.95, 78.0, 0.05, 0.4)};
  stage.summary.fits = {fit};
  return stage;
}

const ModelInfo& Info() {
  static const std::unique_ptr<ModelHandle> model = nomoto::MakeFirstOrderHandle();
  return model->info();
}

std::vector<FindingKind> Kinds(const StageResult& stage) {
  std::vector<FindingKind> kinds;
  for (const Finding& f : stage.findings) kinds.push_back(f.kind);
  return kinds;
}

TEST(StageFindings, GoodStageIsQuiet) {
  StageResult stage = GoodStage();
  DiagnoseStage(Info(), true, &stage);
  EXPECT_TRUE(stage.findings.empty());
  EXPECT_EQ(stage.verdict, Verdict::kGood);
}

TEST(StageFindings, IterationLimitAndNoProgress) {
  StageResult stage = GoodStage();
  stage.summary.refinements[0].termination = "NO_CONVERGENCE";
  stage.summary.refinements[0].message = "Maximum number of iterations reached.";
  DiagnoseStage(Info(), true, &stage);
  EXPECT_EQ(Kinds(stage), std::vector<FindingKind>{FindingKind::kNoConvergence});
  EXPECT_NE(stage.findings[0].message.find("(local.max_iterations)"), std::string::npos);
  // Stopped by its time limit: the finding names that limit.
  stage = GoodStage();
  stage.summary.refinements[0].termination = "NO_CONVERGENCE";
  stage.summary.refinements[0].message = "Maximum solver time reached.";
  DiagnoseStage(Info(), true, &stage);
  ASSERT_EQ(Kinds(stage), std::vector<FindingKind>{FindingKind::kNoConvergence});
  EXPECT_NE(stage.findings[0].message.find("(its time limit, local.max_time)"),
            std::string::npos)
      << stage.findings[0].message;
  // No successful step from the start with a failed fit: it did not search.
  stage = GoodStage();
  stage.summary.refinements[0].successful_steps = 0;
  stage.summary.fits[0].channels[0] = Channel(-0.3, -14.0, 0.5, 0.4);
  DiagnoseStage(Info(), true, &stage);
  ASSERT_EQ(stage.findings.size(), 2u);
  EXPECT_EQ(stage.findings[0].kind, FindingKind::kFailedFit);
  EXPECT_EQ(stage.findings[0].severity, FindingSeverity::kFailure);
  EXPECT_EQ(stage.findings[0].experiment, "run");
  EXPECT_DOUBLE_EQ(stage.findings[0].value, -0.3);
  EXPECT_EQ(stage.findings[1].kind, FindingKind::kNoProgress);
  EXPECT_EQ(stage.findings[1].severity, FindingSeverity::kWarning);
  EXPECT_EQ(stage.verdict, Verdict::kFailed);
  // No successful step from a start that was already the optimum: a note.
  stage = GoodStage();
  stage.summary.refinements[0].successful_steps = 0;
  DiagnoseStage(Info(), true, &stage);
  ASSERT_EQ(stage.findings.size(), 1u);
  EXPECT_EQ(stage.findings[0].severity, FindingSeverity::kInfo);
  EXPECT_EQ(stage.verdict, Verdict::kGood);
  // A regression stage's "solve" is its regression: no solver findings.
  stage = GoodStage();
  stage.summary.refinements[0].successful_steps = 0;
  DiagnoseStage(Info(), false, &stage);
  EXPECT_TRUE(stage.findings.empty());
}

TEST(StageFindings, FitJudgedAgainstWhatTheRecordAllows) {
  // Worse than holding the first value though R2 > 0: failed.
  StageResult stage = GoodStage();
  stage.summary.fits[0].channels[0] = Channel(0.2, 10.0, 0.5, 0.4);
  DiagnoseStage(Info(), true, &stage);
  EXPECT_EQ(Kinds(stage), std::vector<FindingKind>{FindingKind::kFailedFit});
  EXPECT_NE(stage.findings[0].message.find("MAE 0.5 against 0.4 holding"), std::string::npos)
      << stage.findings[0].message;
  // In the unit of the data: a heading logged in degrees.
  DiagnoseStage(Info(), true, &stage, [](const std::string& experiment, const std::string&) {
    return experiment == "run" ? DisplayUnit{"deg", 180.0 / M_PI} : DisplayUnit{"rad", 1.0};
  });
  EXPECT_NE(stage.findings[0].message.find("MAE 28.6 deg against 22.9 deg holding"),
            std::string::npos)
      << stage.findings[0].message;
  // Better than holding, fit 30 %: poor.
  stage = GoodStage();
  stage.summary.fits[0].channels[0] = Channel(0.5, 30.0, 0.2, 0.4);
  DiagnoseStage(Info(), true, &stage);
  EXPECT_EQ(Kinds(stage), std::vector<FindingKind>{FindingKind::kPoorFit});
  EXPECT_EQ(stage.findings[0].threshold, kPoorFitPercent);
  // A record that does not vary beyond its noise (SD 0.1 against noise 0.05) is not judged.
  stage = GoodStage();
  stage.summary.fits[0].channels[0] = Channel(-0.5, -20.0, 0.5, 0.4);
  stage.summary.fits[0].channels[0].noise = 0.05;
  DiagnoseStage(Info(), true, &stage);
  EXPECT_TRUE(stage.findings.empty());
}

// The velocity validation's free runs: R2 < 0 is named per record set and state (a warning
// for a stage, a failure for the final values); the shipped campaigns' good fits (R2 0.98)
// and the one-step predictions are not judged.
TEST(StageFindings, HeldOutFreeRunWorseThanItsMean) {
  auto metric = [](const std::string& prediction, const std::string& state, double r2) {
    ChannelMetrics m;
    m.experiment = prediction;
    m.output = state;
    m.samples = 4786;
    m.r2 = r2;
    return m;
  };
  StageResult stage = GoodStage();
  stage.velocity_validation = {metric("validation one-step", "v", -0.5),
                               metric("validation free-run", "u", 0.98),
                               metric("validation free-run", "v", -5.2)};
  DiagnoseStage(Info(), true, &stage);
  ASSERT_EQ(Kinds(stage), std::vector<FindingKind>{FindingKind::kHeldOutFreeRunFailed});
  EXPECT_EQ(stage.findings[0].severity, FindingSeverity::kWarning);
  EXPECT_EQ(stage.findings[0].output, "v");
  EXPECT_EQ(stage.findings[0].message,
            "the held-out free run of validation predicts v worse than its mean (R2 -5.2 over "
            "4786 samples)");
  std::vector<Finding> final_findings;
  AddFreeRunFindings(stage.velocity_validation, "final", FindingSeverity::kFailure,
                     &final_findings);
  ASSERT_EQ(final_findings.size(), 1u);
  EXPECT_EQ(final_findings[0].severity, FindingSeverity::kFailure);
  stage.velocity_validation[2].r2 = 0.98;
  DiagnoseStage(Info(), true, &stage);
  EXPECT_TRUE(stage.findings.empty());
}

TEST(StageFindings, WeaklyDeterminedAndNotAdmissible) {
  StageResult stage = GoodStage();
  stage.estimates[0].std_error = 1.5;  // T = 2 +- 1.5: 75 %
  stage.admissibility = {"T must be > 0"};
  DiagnoseStage(Info(), true, &stage);
  ASSERT_EQ(stage.findings.size(), 2u);
  EXPECT_EQ(stage.findings[0].kind, FindingKind::kWeaklyDetermined);
  EXPECT_NEAR(stage.findings[0].value, 0.75, 1e-12);
  EXPECT_NE(stage.findings[0].message.find("T = 2 +- 1.5 (75 %, sign unknown)"), std::string::npos)
      << stage.findings[0].message;
  EXPECT_EQ(stage.findings[1].kind, FindingKind::kNotAdmissible);
  EXPECT_EQ(stage.findings[1].severity, FindingSeverity::kWarning);
}

// An interval that spans 0 leaves the sign unknown, however small the value is beside its
// bound range: a note saying so (the fit hardly depends on such a term); near 0 with a tight
// interval it is determined and quiet; a relative error above 50 % stays a warning.
TEST(StageFindings, SignUnknownWhenTheIntervalSpansZero) {
  StageResult stage = GoodStage();
  stage.estimates[1] = Free("K", 0.386, 0.49);
  stage.estimates[1].lower = -1000.0;
  stage.estimates[1].upper = 10000.0;
  DiagnoseStage(Info(), true, &stage);
  ASSERT_EQ(stage.findings.size(), 1u);
  EXPECT_EQ(stage.findings[0].kind, FindingKind::kWeaklyDetermined);
  EXPECT_EQ(stage.findings[0].severity, FindingSeverity::kInfo);
  EXPECT_NE(stage.findings[0].message.find("K = 0.386 +- 0.49 (127 %, sign unknown)"),
            std::string::npos)
      << stage.findings[0].message;
  EXPECT_EQ(stage.verdict, Verdict::kGood);
  stage = GoodStage();
  stage.estimates[1] = Free("K", 0.386, 0.049);
  stage.estimates[1].lower = -1000.0;
  stage.estimates[1].upper = 10000.0;
  DiagnoseStage(Info(), true, &stage);
  EXPECT_TRUE(stage.findings.empty());
  stage = GoodStage();
  stage.estimates[1] = Free("K", 0.386, 0.49);  // bounds -10..10: 0.49 / 0.386 is poor
  DiagnoseStage(Info(), true, &stage);
  ASSERT_EQ(stage.findings.size(), 1u);
  EXPECT_EQ(stage.findings[0].severity, FindingSeverity::kWarning);
}

// On a bound whose other side is open (N_r <= 0): at_bound all the same; off it, quiet.
TEST(StageFindings, AtABoundWithTheOtherSideOpen) {
  StageResult stage = GoodStage();
  stage.estimates[1] = Free("K", 0.0, 0.001);
  stage.estimates[1].lower = -std::numeric_limits<double>::infinity();
  stage.estimates[1].upper = 0.0;
  DiagnoseStage(Info(), true, &stage);
  ASSERT_EQ(stage.findings.size(), 1u);
  EXPECT_EQ(stage.findings[0].kind, FindingKind::kAtBound);
  EXPECT_NE(stage.findings[0].message.find("upper bound 0"), std::string::npos);
  stage = GoodStage();
  stage.estimates[1] = Free("K", -0.17, 0.001);
  stage.estimates[1].lower = -std::numeric_limits<double>::infinity();
  stage.estimates[1].upper = 0.0;
  DiagnoseStage(Info(), true, &stage);
  EXPECT_TRUE(stage.findings.empty());
}

// Coloured residuals of psi on 1000 samples, whiteness rejected, with the given lag-1.
ResidualAnalysis ColouredPsi(double lag1) {
  ResidualAnalysis a;
  a.experiment = "run";
  a.output = "psi";
  a.samples = 1000;
  a.lags = 25;
  a.lag1 = lag1;
  a.ljung_box_p = 1e-9;
  a.white = false;
  a.band_99 = 2.5758 / std::sqrt(1000.0);
  return a;
}

// Coloured residuals are a note when Ljung-Box rejects whiteness and the lag-1 autocorrelation
// is beyond its 99 % band, as the rule says; a rejection at far lags with lag-1 0.00 is no
// such note.
TEST(StageFindings, ColouredResidualsNeedTheLagOneCorrelation) {
  for (double lag1 : {0.0, 0.8}) {
    StageResult stage = GoodStage();
    stage.residuals = {ColouredPsi(lag1)};
    DiagnoseStage(Info(), true, &stage);
    const std::vector<FindingKind> kinds = Kinds(stage);
    EXPECT_EQ(std::count(kinds.begin(), kinds.end(), FindingKind::kColouredResiduals),
              lag1 > 0.3 ? 1 : 0)
        << lag1;
  }
}

// Pieces skipped in several records are one finding with the counts and the shortest piece;
// one piece alone stays as it is.
TEST(RunFindings, SkippedPiecesAreOneFindingWithTheWorstCase) {
  std::vector<Finding> findings;
  const double lengths[] = {3.0, 0.4, 2.0, 5.0, 1.5};
  for (int i = 0; i < 5; ++i) {
    Finding f = MakeFinding(FindingKind::kSegmentSkipped,
                            "skipped (t = 0 to 1 s): fewer samples than the smoothing window");
    f.experiment = i < 3 ? "log1" : "log2";
    f.segment = f.experiment + "#" + std::to_string(i);
    f.value = lengths[i];
    findings.push_back(f);
  }
  Finding other = MakeFinding(FindingKind::kAtBound, "T is at its bound");
  other.stage = "fit";
  findings.push_back(other);
  const std::vector<Finding> folded = FoldFindings(findings);
  ASSERT_EQ(folded.size(), 2u);
  const Finding& skipped = folded[0].kind == FindingKind::kSegmentSkipped ? folded[0] : folded[1];
  EXPECT_EQ(skipped.count, 5);
  EXPECT_DOUBLE_EQ(skipped.value, 0.4);
  EXPECT_TRUE(skipped.experiment.empty());
  EXPECT_NE(skipped.message.find("5 pieces of 2 record(s) skipped (log1, log2); the shortest, "
                                 "0.4 s (log1, log1#1)"),
            std::string::npos)
      << skipped.message;
  findings.resize(1);
  ASSERT_EQ(FoldFindings(findings).size(), 1u);
  EXPECT_EQ(FoldFindings(findings)[0].message, findings[0].message);
}

// Strong structure (lag-1 above 0.3 where the RMSE is above 1.05 x the record's noise level)
// is a warning; the same colour at the noise level (a residual that is mostly noise) a note.
TEST(StageFindings, StrongResidualStructureIsAWarning) {
  for (double noise : {0.001, 0.098}) {
    StageResult stage = GoodStage();  // its fit: RMSE 0.1
    stage.summary.fits[0].channels[0].noise = noise;
    stage.residuals = {ColouredPsi(0.9)};
    DiagnoseStage(Info(), true, &stage);
    ASSERT_EQ(stage.findings.size(), 1u) << noise;
    EXPECT_EQ(stage.findings[0].kind, FindingKind::kColouredResiduals);
    const bool strong = noise < 0.01;
    EXPECT_EQ(stage.findings[0].severity,
              strong ? FindingSeverity::kWarning : FindingSeverity::kInfo);
    EXPECT_EQ(stage.verdict, strong ? Verdict::kDoubtful : Verdict::kGood);
  }
}

// A residual the noise on a measured input can make (its share from the input noise refits,
// input_noise_uncertainty.h) is noise, not structure: a note, however coloured, that says so.
TEST(StageFindings, ColourTheInputNoiseMakesIsANote) {
  for (double share : {0.0, 0.5, 0.9995}) {
    StageResult stage = GoodStage();  // its fit: RMSE 0.1
    stage.summary.fits[0].channels[0].noise = 0.05;
    ResidualAnalysis a = ColouredPsi(0.85);
    a.input_noise_share = share;
    stage.residuals = {a};
    DiagnoseStage(Info(), true, &stage);
    ASSERT_EQ(stage.findings.size(), 1u) << share;
    // Without the input noise's part the RMSE is 0.1 sqrt(1 - share): 2, 1.41, 0.06 x noise.
    const bool strong = share < 0.99;
    EXPECT_EQ(stage.findings[0].severity,
              strong ? FindingSeverity::kWarning : FindingSeverity::kInfo) << share;
    EXPECT_EQ(stage.findings[0].message.find("of the residual power is the noise on a measured "
                                             "input") != std::string::npos,
              share >= 0.1)
        << stage.findings[0].message;
  }
}

TEST(RunFindings, FinalValuesAndTheVerdictRule) {
  RunConfig config;
  config.model = nomoto::MakeFirstOrderHandle();
  RunResult run;
  run.stages = {GoodStage(), GoodStage()};
  run.stages[0].name = "start";
  run.stages[0].summary.fits[0].channels[0] = Channel(0.5, 30.0, 0.2, 0.4);  // poor: a start
  run.admissibility = {"T must be > 0"};
  ExperimentFit held;
  held.experiment = "check";
  held.channels = {Channel(0.3, 5.0, 0.6, 0.4)};
  run.final_validation = {held};
  DiagnoseRun(config, &run);
  // The start stage's doubt stays with it; the final values' failures judge the run.
  EXPECT_EQ(run.stages[0].verdict, Verdict::kDoubtful);
  EXPECT_EQ(run.stages[1].verdict, Verdict::kGood);
  ASSERT_EQ(run.findings.size(), 2u);
  for (const Finding& f : run.findings) {
    EXPECT_EQ(f.severity, FindingSeverity::kFailure);
    EXPECT_EQ(f.stage, "final");
  }
  EXPECT_EQ(run.findings[0].kind, FindingKind::kNotAdmissible);
  EXPECT_EQ(run.findings[1].kind, FindingKind::kFinalHeldOutFailed);
  EXPECT_NEAR(run.findings[1].value, 1.5, 1e-12);
  EXPECT_EQ(run.verdict, Verdict::kFailed);
}

}  // namespace stage_findings_test
}  // namespace vesselid

// The staged pipeline: carried starts, isolated and shared roles, fusion rules, local and
// final validation, per-stage model restriction, and undetermined combinations.
#include "engine/run/pipeline.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include "engine/config/config.h"
#include "engine/diagnose/run_findings.h"
#include "engine/output/run_traces.h"
#include "engine/run/records.h"
#include "engine/solve/step_stability.h"
#include "gtest/gtest.h"
#include "tests/support/findings.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"
#include "problems/registry.h"

namespace vesselid {
namespace pipeline_test {

namespace fs = std::filesystem;

class PipelineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vesselid_pipeline_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // Three first-order runs (T 2 s, K -0.17) with different heading noise.
    auto model = nomoto::MakeFirstOrderHandle();
    const double noise[] = {0.002, 0.01, 0.001};
    for (int i = 0; i < 3; ++i) {
      nomoto::ClosedLoopOptions loop;
      loop.duration = 120.0;
      loop.sample_time = 0.05;
      loop.controller_gain = 0.7;
      loop.excitation.amplitude = 0.3;
      loop.excitation.periods = {15.0 + 5 * i};
      loop.heading_noise = noise[i];
      loop.seed = 10 + i;
      Trajectory data;
      std::string error;
      ASSERT_TRUE(nomoto::SimulateClosedLoop(*model, {2.0, -0.17, 0.0}, loop, &data, &error));
      ASSERT_TRUE(WriteTrajectoryCsv((dir_ / ("run" + std::to_string(i) + ".csv")).string(),
                                     data, &error));
    }
    // A record of another vessel (T 4 s, K -0.3): data whose structure is not the others'.
    nomoto::ClosedLoopOptions loop;
    loop.duration = 120.0;
    loop.sample_time = 0.05;
    loop.controller_gain = 0.7;
    loop.excitation.amplitude = 0.3;
    loop.excitation.periods = {20.0};
    loop.heading_noise = 0.002;
    loop.seed = 20;
    Trajectory data;
    std::string error;
    ASSERT_TRUE(nomoto::SimulateClosedLoop(*model, {4.0, -0.3, 0.0}, loop, &data, &error));
    ASSERT_TRUE(WriteTrajectoryCsv((dir_ / "other.csv").string(), data, &error));
  }
  void TearDown() override { fs::remove_all(dir_); }

  RunResult Run(const std::string& stages_and_more) {
    const std::string text = R"(model: {family: nomoto, type: first_order}
experiments:
  - {name: a, file: run0.csv, inputs: {delta: delta}, outputs: {psi: psi}}
  - {name: b, file: run1.csv, inputs: {delta: delta}, outputs: {psi: psi}}
  - {name: c, file: run2.csv, inputs: {delta: delta}, outputs: {psi: psi}}
  - {name: other, file: other.csv, inputs: {delta: delta}, outputs: {psi: psi}}
)" + stages_and_more;
    std::ofstream(dir_ / "run.yaml") << text;
    RunConfig config;
    RunResult result;
    std::string error;
    const ModelRegistry registry = DefaultRegistry();
    EXPECT_TRUE(LoadRunConfig((dir_ / "run.yaml").string(), "", registry, &config, &error))
        << error;
    EXPECT_TRUE(Identify(config, &result, &error)) << error;
    return result;
  }

  // A finding of `kind` and `severity` whose line (DescribeFinding) contains `text`.
  static bool Has(const RunResult& result, FindingKind kind, FindingSeverity severity,
                  const std::string& text) {
    for (const Finding& f : testing::FindingsOf(result, &kind, text)) {
      if (f.severity == severity) return true;
    }
    return false;
  }

  static const Estimate& Find(const StageResult& stage, const std::string& name) {
    for (const Estimate& e : stage.estimates) {
      if (e.name == name) return e;
    }
    throw std::runtime_error("no estimate " + name);
  }
  static const FinalParameter& Final(const RunResult& result, const std::string& name) {
    for (const FinalParameter& f : result.parameters) {
      if (f.name == name) return f;
    }
    throw std::runtime_error("no parameter " + name);
  }

  fs::path dir_;
};

const char* kTwoStages = R"(stages:
  - name: first
    experiments: [a]
    validation: [c]
    free_initial_states: [psi]
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20, role: shared}
      K: {start: -0.1, lower: -1, upper: -0.001, role: shared}
  - name: second
    experiments: [b]
    free_initial_states: [psi]
    parameters:
      T: {lower: 0.1, upper: 20, role: shared}
      K: {lower: -1, upper: -0.001, role: isolated}
final_validation: {experiments: [c]}
)";

TEST_F(PipelineTest, SharedParametersFuseByInverseVarianceOrMean) {
  RunResult weighted = Run(kTwoStages);
  RunResult mean = Run(std::string(kTwoStages) + "fusion: mean\n");
  ASSERT_EQ(weighted.stages.size(), 2u);
  // The second stage starts where the first ended.
  EXPECT_DOUBLE_EQ(Find(weighted.stages[1], "T").start, Find(weighted.stages[0], "T").value);
  const Estimate& t1 = Find(weighted.stages[0], "T");
  const Estimate& t2 = Find(weighted.stages[1], "T");
  // Noisier second run: larger standard error, so the rules differ.
  ASSERT_GT(t2.std_error, 2 * t1.std_error);
  const double w1 = 1 / (t1.std_error * t1.std_error), w2 = 1 / (t2.std_error * t2.std_error);
  const FinalParameter& fused = Final(weighted, "T");
  EXPECT_NEAR(fused.value, (w1 * t1.value + w2 * t2.value) / (w1 + w2), 1e-12);
  EXPECT_NEAR(fused.std_error, 1 / std::sqrt(w1 + w2), 1e-12);
  EXPECT_EQ(fused.rule, "inverse_variance");
  EXPECT_EQ(fused.stages, (std::vector<std::string>{"first", "second"}));
  const FinalParameter& averaged = Final(mean, "T");
  EXPECT_NEAR(averaged.value, 0.5 * (t1.value + t2.value), 1e-12);
  EXPECT_EQ(averaged.rule, "mean");
  EXPECT_GT(std::abs(fused.value - averaged.value), 1e-4);
  // Both within their reported uncertainty of the truth; the weighted one is closer here.
  EXPECT_LT(std::abs(fused.value - 2.0), 3 * fused.std_error);
  // K is isolated in the last stage that estimated it: its value, not a fusion.
  EXPECT_EQ(Final(weighted, "K").rule, "stage");
  EXPECT_DOUBLE_EQ(Final(weighted, "K").value, Find(weighted.stages[1], "K").value);
  // Local and final validation on the held-out run c.
  ASSERT_EQ(weighted.stages[0].validation.size(), 1u);
  ASSERT_EQ(weighted.final_validation.size(), 1u);
  EXPECT_GT(weighted.final_validation[0].channels[0].r2, 0.999);
}

// With one shared parameter, information fusion reduces to inverse-variance weighting.
TEST_F(PipelineTest, InformationFusionOfOneParameterIsInverseVariance) {
  RunResult weighted = Run(kTwoStages);
  RunResult joint = Run(std::string(kTwoStages) + "fusion: information\n");
  EXPECT_NEAR(Final(joint, "T").value, Final(weighted, "T").value, 1e-9);
  EXPECT_NEAR(Final(joint, "T").std_error, Final(weighted, "T").std_error, 1e-9);
  EXPECT_EQ(Final(joint, "T").rule, "information");
}

// T is 2 s; a bound at 1.5 s stops it there, and the stage says so.
TEST_F(PipelineTest, EstimateOnItsBoundIsReported) {
  RunResult result = Run(R"(stages:
  - name: bounded
    experiments: [a]
    free_initial_states: [psi]
    parameters:
      T: {start: 1.0, lower: 0.1, upper: 1.5}
      K: {start: -0.1, lower: -1, upper: -0.001}
)");
  const std::vector<Finding>& findings = result.stages[0].findings;
  ASSERT_FALSE(findings.empty());
  EXPECT_EQ(findings[0].kind, FindingKind::kAtBound);
  EXPECT_EQ(findings[0].parameter, "T");
  EXPECT_EQ(findings[0].threshold, 1.5);
  EXPECT_NE(findings[0].message.find(" is at its upper bound 1.5 s: the data pull it further"),
            std::string::npos)
      << findings[0].message;
}

TEST_F(PipelineTest, UnlistedParametersAreHeldAtTheirLatestEstimate) {
  RunResult result = Run(R"(stages:
  - name: both
    experiments: [a, c]
    free_initial_states: [psi]
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20}
      K: {start: -0.1, lower: -1, upper: -0.001}
  - name: bias_only
    experiments: [b]
    free_initial_states: [psi]
    parameters:
      delta_0: {start: 0.0, lower: -0.1, upper: 0.1}
)");
  ASSERT_EQ(result.stages.size(), 2u);
  EXPECT_DOUBLE_EQ(Find(result.stages[1], "T").value, Find(result.stages[0], "T").value);
  EXPECT_EQ(Find(result.stages[1], "T").role, ParameterRole::kFixed);
  EXPECT_EQ(Final(result, "T").stages, (std::vector<std::string>{"both"}));
  EXPECT_NEAR(Final(result, "delta_0").value, 0.0, 3 * Final(result, "delta_0").std_error);
}

TEST_F(PipelineTest, CarriedStartOutsideBoundsIsAnError) {
  std::ofstream(dir_ / "run.yaml") << R"(model: {family: nomoto, type: first_order}
experiments:
  - {name: a, file: run0.csv, inputs: {delta: delta}, outputs: {psi: psi}}
stages:
  - name: first
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20}
      K: {start: -0.17, role: fixed}
  - name: second
    parameters:
      T: {lower: 5, upper: 20}
)";
  RunConfig config;
  RunResult result;
  std::string error;
  ASSERT_TRUE(LoadRunConfig((dir_ / "run.yaml").string(), "", DefaultRegistry(), &config, &error));
  EXPECT_FALSE(Identify(config, &result, &error));
  EXPECT_NE(error.find("stage 'second': parameter 'T': carried start"), std::string::npos) << error;
}

// A refinement on a record of another vessel is worse on the held-out run than the stage it
// started from: the run says so and, by default, keeps the better estimate.
const char* kRefinedOnAnotherVessel = R"(stages:
  - name: first
    experiments: [a]
    validation: [c]
    free_initial_states: [psi]
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20}
      K: {start: -0.1, lower: -1, upper: -0.001}
  - name: refinement
    experiments: [other]
    validation: [c]
    free_initial_states: [psi]
    parameters:
      T: {}
      K: {}
final_validation: {experiments: [c]}
)";

TEST_F(PipelineTest, StageWorseOnHeldOutDataIsSetAsideAndNamed) {
  RunResult result = Run(kRefinedOnAnotherVessel);
  ASSERT_EQ(result.stages.size(), 2u);
  const StageResult& refinement = result.stages[1];
  ASSERT_TRUE(refinement.held_out.done);
  EXPECT_TRUE(refinement.held_out.worse);
  EXPECT_FALSE(refinement.rejected.empty());
  EXPECT_TRUE(result.stages[0].rejected.empty());
  EXPECT_NEAR(Find(refinement, "T").value, 4.0, 0.2);  // what the other vessel has
  // The final values are the first stage's, the better one on held-out data.
  EXPECT_DOUBLE_EQ(Final(result, "T").value, Find(result.stages[0], "T").value);
  EXPECT_EQ(Final(result, "T").stages, (std::vector<std::string>{"first"}));
  EXPECT_TRUE(Has(result, FindingKind::kStageSetAside, FindingSeverity::kWarning,
                  "stage 'refinement': worse on held-out data than its start"));
  // The final values are the first stage's: the run's verdict says a stage was set aside.
  EXPECT_EQ(result.verdict, Verdict::kDoubtful);
  EXPECT_GT(result.final_validation[0].channels[0].r2, 0.999);
}

TEST_F(PipelineTest, FinalLastKeepsTheWorseStageWithAWarning) {
  RunResult result = Run(std::string(kRefinedOnAnotherVessel) + "final: last\n");
  ASSERT_EQ(result.stages.size(), 2u);
  EXPECT_TRUE(result.stages[1].rejected.empty());
  EXPECT_NEAR(Final(result, "T").value, 4.0, 0.2);
  EXPECT_TRUE(Has(result, FindingKind::kHeldOutWorse, FindingSeverity::kWarning,
                  "stage 'refinement': worse on held-out data than its start"));
  EXPECT_EQ(result.stages[1].verdict, Verdict::kDoubtful);
}

// A carried parameter listed without bounds keeps the bounds of the stage that estimated it.
TEST_F(PipelineTest, CarriedParameterKeepsItsEarlierBounds) {
  RunResult result = Run(R"(stages:
  - name: first
    experiments: [a]
    free_initial_states: [psi]
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20}
      K: {start: -0.1, lower: -1, upper: -0.001}
  - name: second
    experiments: [b]
    free_initial_states: [psi]
    parameters:
      T: {}
      K: {lower: -0.5}
)");
  ASSERT_EQ(result.stages.size(), 2u);
  EXPECT_EQ(Find(result.stages[1], "T").lower, 0.1);
  EXPECT_EQ(Find(result.stages[1], "T").upper, 20.0);
  EXPECT_EQ(Find(result.stages[1], "K").lower, -0.5);  // given: the stage's own
  EXPECT_EQ(Find(result.stages[1], "K").upper, -0.001);
}

// A per-experiment rudder bias with a validation run: the held-out run estimates its own bias
// (and, under the sanitizers, without reading past the stage's values).
TEST_F(PipelineTest, PerExperimentParameterWithValidation) {
  RunResult result = Run(R"(stages:
  - name: biased
    experiments: [a, b]
    validation: [c]
    free_initial_states: [psi]
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20}
      K: {start: -0.1, lower: -1, upper: -0.001}
      delta_0: {start: 0.0, lower: -0.1, upper: 0.1, role: per_experiment}
)");
  ASSERT_EQ(result.stages.size(), 1u);
  ASSERT_EQ(result.stages[0].validation.size(), 1u);
  EXPECT_FALSE(result.stages[0].validation[0].diverged);
  EXPECT_GT(result.stages[0].validation[0].channels[0].r2, 0.999);
}

// A time constant (0.3 s) shorter than the sample interval (1 s, the default step) is past
// RK4's accuracy: the stage shortens the step, refines again and finds the vessel's value
// instead of one the integrator makes. Data: the exact discrete response to a held rudder.
TEST_F(PipelineTest, StepTooLongForTheDynamicsIsShortened) {
  const double T = 0.3, K = -0.17, h = 1.0, a = std::exp(-h / T);
  Trajectory data;
  data.names = {"delta", "psi"};
  data.columns.resize(2);
  double r = 0.0, psi = 0.0;
  for (int k = 0; k <= 300; ++k) {
    const double delta = (k / 10) % 2 == 0 ? 0.2 : -0.1;
    data.t.push_back(k * h);
    data.columns[0].push_back(delta);
    data.columns[1].push_back(psi);
    const double r_next = a * r + (1 - a) * K * delta;
    psi += K * delta * h - T * (r_next - r);
    r = r_next;
  }
  std::string error;
  ASSERT_TRUE(WriteTrajectoryCsv((dir_ / "fast.csv").string(), data, &error)) << error;
  std::ofstream(dir_ / "run.yaml") << R"(model: {family: nomoto, type: first_order}
experiments:
  - {name: fast, file: fast.csv, inputs: {delta: delta}, outputs: {psi: psi},
     interpolation: zero_order_hold}
stages:
  - name: fit
    parameters:
      T: {start: 3.0, lower: 0.01, upper: 20}
      K: {start: -0.1, lower: -1, upper: -0.001}
)";
  RunConfig config;
  RunResult result;
  ASSERT_TRUE(LoadRunConfig((dir_ / "run.yaml").string(), "", DefaultRegistry(), &config, &error));
  ASSERT_TRUE(Identify(config, &result, &error)) << error;
  const StageResult& stage = result.stages[0];
  EXPECT_GT(stage.integration_step, 0.0);
  EXPECT_LE(stage.integration_step, T * kStepStabilityLimit);
  EXPECT_NEAR(Find(stage, "T").value, T, 0.01 * T);
  EXPECT_NEAR(Find(stage, "K").value, K, 0.01 * std::abs(K));
  // Handled by the stage: a note, not a doubt.
  EXPECT_TRUE(Has(result, FindingKind::kIntegrationStep, FindingSeverity::kInfo,
                  "integration step reduced"));
}

// continuation on a record split by a segment column cuts each segment into pieces (it was
// once a silent no-op there), and the held-out segments are validated.
TEST_F(PipelineTest, ContinuationOnSegmentColumnRecords) {
  Trajectory data;
  std::string error;
  ASSERT_TRUE(ReadTrajectoryCsv((dir_ / "run0.csv").string(), &data, &error)) << error;
  data.names.push_back("segment");
  data.columns.emplace_back();
  for (double t : data.t) data.columns.back().push_back(t < 40 ? 1 : t < 80 ? 2 : 3);
  ASSERT_TRUE(WriteTrajectoryCsv((dir_ / "segmented.csv").string(), data, &error)) << error;
  std::ofstream(dir_ / "run.yaml") << R"(model: {family: nomoto, type: first_order}
experiments:
  - {name: train, file: segmented.csv, inputs: {delta: delta}, outputs: {psi: psi},
     segments: {column: segment, take: training, validation_share: 0.34, seed: 2}}
  - {name: held, file: segmented.csv, inputs: {delta: delta}, outputs: {psi: psi},
     segments: {column: segment, take: validation, validation_share: 0.34, seed: 2}}
stages:
  - name: fit
    experiments: [train]
    validation: [held]
    free_initial_states: [psi, r]
    continuation: [10]
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20}
      K: {start: -0.1, lower: -1, upper: -0.001}
)";
  RunConfig config;
  RunResult result;
  ASSERT_TRUE(LoadRunConfig((dir_ / "run.yaml").string(), "", DefaultRegistry(), &config, &error));
  ASSERT_TRUE(Identify(config, &result, &error)) << error;
  const std::vector<std::string>& notes = result.stages[0].summary.notes;
  ASSERT_FALSE(notes.empty());
  EXPECT_EQ(notes[0].rfind("continuation: 10 s segments (8 pieces)", 0), 0u) << notes[0];
  EXPECT_NEAR(Find(result.stages[0], "T").value, 2.0, 0.05);
  ASSERT_EQ(result.stages[0].validation.size(), 1u);
  EXPECT_FALSE(result.stages[0].validation[0].diverged);
  // One trace per record, its segments one after another with their ids in `segment`: each
  // segment's rows are its fit's trace.
  const std::vector<NamedTrace> traces = RunTraces(config, result);
  ASSERT_EQ(traces.size(), 2u);
  EXPECT_EQ(traces[0].name, "fit.train");
  EXPECT_EQ(traces[0].file, "fit.train.csv");
  EXPECT_EQ(traces[1].name, "fit.validation.held");
  const Trajectory& joined = traces[0].trace;
  ASSERT_EQ(joined.names[0], "segment");
  const std::vector<ExperimentFit>& fits = result.stages[0].summary.fits;
  ASSERT_EQ(fits.size(), 2u);
  size_t row = 0;
  for (const ExperimentFit& fit : fits) {
    const double id = std::stod(fit.experiment.substr(fit.experiment.find('@') + 1));
    const int simulated = joined.Find("psi_simulated [rad]");
    ASSERT_GE(simulated, 0);
    for (size_t k = 0; k < fit.trace.t.size(); ++k, ++row) {
      ASSERT_LT(row, joined.t.size());
      EXPECT_EQ(joined.t[row], fit.trace.t[k]);
      EXPECT_EQ(joined.columns[0][row], id);
      EXPECT_EQ(joined.columns[simulated][row],
                fit.trace.columns[fit.trace.Find("psi_simulated")][k]);
    }
  }
  EXPECT_EQ(row, joined.t.size());
}

// A model that is stable on the small manoeuvres it was fitted to and diverges on a larger
// held-out one (Norrbin with a destabilising cubic term): the held-out run is recorded as
// diverged, with where, and the run goes on.
TEST_F(PipelineTest, HeldOutRunThatDivergesIsRecordedAndTheRunGoesOn) {
  auto model = nomoto::MakeFirstOrderHandle();
  for (const auto& [name, amplitude] : {std::pair{"calm", 0.02}, std::pair{"hard", 0.6}}) {
    nomoto::ClosedLoopOptions loop;
    loop.duration = 120.0;
    loop.sample_time = 0.05;
    loop.controller_gain = 0.7;
    loop.excitation.amplitude = amplitude;
    loop.excitation.periods = {20.0};
    Trajectory data;
    std::string error;
    ASSERT_TRUE(nomoto::SimulateClosedLoop(*model, {2.0, -0.17, 0.0}, loop, &data, &error));
    ASSERT_TRUE(WriteTrajectoryCsv((dir_ / (std::string(name) + ".csv")).string(), data, &error));
  }
  std::ofstream(dir_ / "run.yaml") << R"(model: {family: nomoto, type: norrbin}
experiments:
  - {name: calm, file: calm.csv, inputs: {delta: delta}, outputs: {psi: psi}}
  - {name: hard, file: hard.csv, inputs: {delta: delta}, outputs: {psi: psi}}
stages:
  - name: fit
    experiments: [calm]
    validation: [hard]
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 20}
      K: {start: -0.1, lower: -1, upper: -0.001}
      alpha: {start: -400, role: fixed}
final_validation: {experiments: [hard]}
)";
  RunConfig config;
  RunResult result;
  std::string error;
  ASSERT_TRUE(LoadRunConfig((dir_ / "run.yaml").string(), "", DefaultRegistry(), &config, &error));
  ASSERT_TRUE(Identify(config, &result, &error)) << error;
  ASSERT_EQ(result.stages[0].validation.size(), 1u);
  const ExperimentFit& held = result.stages[0].validation[0];
  EXPECT_TRUE(held.diverged);
  EXPECT_NE(held.message.find("experiment 'hard' diverges after t = "), std::string::npos)
      << held.message;
  ASSERT_EQ(result.final_validation.size(), 1u);
  EXPECT_TRUE(result.final_validation[0].diverged);
  EXPECT_TRUE(Has(result, FindingKind::kHeldOutDiverged, FindingSeverity::kFailure,
                  "stage 'fit', experiment 'hard': simulation of experiment 'hard'"));
  EXPECT_TRUE(Has(result, FindingKind::kFinalHeldOutFailed, FindingSeverity::kFailure,
                  "stage final, experiment 'hard': diverges: simulation of experiment 'hard'"));
  EXPECT_EQ(result.verdict, Verdict::kFailed);
}

}  // namespace pipeline_test
}  // namespace vesselid

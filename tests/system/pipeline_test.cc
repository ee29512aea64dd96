// The staged pipeline: carried starts, isolated and shared roles, fusion rules, local and
// final validation, per-stage model restriction, and undetermined combinations.
#include <cmath>
#include <filesystem>
#include <fstream>

#include "engine/config/config.h"
#include "engine/run/pipeline.h"
#include "engine/run/records.h"
#include "gtest/gtest.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"
#include "problems/registry.h"

namespace vesselid {
namespace {

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
  }
  void TearDown() override { fs::remove_all(dir_); }

  RunResult Run(const std::string& stages_and_more) {
    const std::string text = R"(model: {family: nomoto, type: first_order}
experiments:
  - {name: a, file: run0.csv, inputs: {delta: delta}, outputs: {psi: psi}}
  - {name: b, file: run1.csv, inputs: {delta: delta}, outputs: {psi: psi}}
  - {name: c, file: run2.csv, inputs: {delta: delta}, outputs: {psi: psi}}
)" + stages_and_more;
    std::ofstream(dir_ / "run.yaml") << text;
    RunConfig config;
    RunResult result;
    std::string error;
    const ModelRegistry registry = DefaultRegistry();
    EXPECT_TRUE(LoadRunConfig((dir_ / "run.yaml").string(), "", registry, &config, &error))
        << error;
    EXPECT_TRUE(RunIdentification(config, &result, &error)) << error;
    return result;
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
  const std::vector<std::string>& notes = result.stages[0].summary.notes;
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0].rfind("T is at its upper bound 1.5", 0), 0u) << notes[0];
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
  EXPECT_FALSE(RunIdentification(config, &result, &error));
  EXPECT_NE(error.find("stage 'second': parameter 'T': carried start"), std::string::npos) << error;
}

}  // namespace
}  // namespace vesselid

// Simulations that diverge for some parameters are rejected cleanly by every solver: the
// global search scores them and goes on, a local solve rejects the step (or, at the start
// values, stops the run with a message and no results), and each study records the case
// as failed and goes on. Data: seed 003's patrol vessel; bounds that let T1, T2 and T3 go
// negative, where the second-order Nomoto model is unstable and its simulation overflows.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/patrol_config.h"
#include "tests/support/study_cli.h"

namespace vesselid {
namespace divergence_test {

using nlohmann::json;
namespace fs = std::filesystem;

std::string ConfigText() {
  return testing::PatrolConfigHead(300) + R"(
stages:
  - name: second_order
    parameters:
      T1: {start: T1_START, lower: -5.0, upper: 20.0}
      T2: {start: 0.2, lower: -5.0, upper: 20.0}
      T3: {start: 0.27, lower: -5.0, upper: 5.0}
      K: {start: -0.11, lower: -2.0, upper: 2.0}
    GLOBAL
study:
  seed: 1
  starts: {runs: 6}
  profile: {stage: second_order, parameters: [T1], points: 5, span: 1.0e8}
  monte_carlo: {runs: 3, noise: {psi: 0.001}, start: stage,
                truth: {T1: 2.0875, T2: 0.3179, T3: 0.1830, K: -0.1724}}
)";
}

std::string Config(const std::string& t1_start, const std::string& global) {
  std::string text = ConfigText();
  text.replace(text.find("T1_START"), 8, t1_start);
  text.replace(text.find("GLOBAL"), 6, global);
  return text;
}

class DivergenceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new testing::StudyFolder("vesselid_divergence");
    std::ofstream(folder_->dir() / "global.yaml")
        << Config("3.0", "global: {algorithm: GN_CRS2_LM, max_evaluations: 150, seed: 1}");
    std::ofstream(folder_->dir() / "diverging_start.yaml") << Config("-3.0", "");
    // A finished stage, then one that diverges at its start values.
    std::ofstream(folder_->dir() / "second_diverges.yaml") << testing::PatrolConfigHead(300) + R"(
stages:
  - name: first
    parameters:
      T1: {start: 3.0, lower: 0.01, upper: 20.0}
      T2: {start: 0.2, lower: 0.01, upper: 20.0}
      T3: {start: 0.27, lower: 0.0, upper: 5.0}
      K: {start: -0.11, lower: -2.0, upper: 2.0}
  - name: second
    parameters:
      T1: {start: -3.0, lower: -5.0, upper: 20.0}
)";
    folder_->Simulate("global.yaml");
  }
  static void TearDownTestSuite() { delete folder_; }

  static json Results(const std::string& out) {
    std::ifstream in(folder_->dir() / out / "results.json");
    EXPECT_TRUE(in.good()) << "no results.json in " << out;
    return json::parse(in, nullptr, false);
  }

  static testing::StudyFolder* folder_;
};

testing::StudyFolder* DivergenceTest::folder_ = nullptr;

TEST_F(DivergenceTest, GlobalSearchScoresDivergingPointsAndFindsTheTruth) {
  std::string messages;
  ASSERT_EQ(folder_->Run("global.yaml", "global", &messages), 0) << messages;
  const json stage = Results("global")["stages"][0];
  EXPECT_GT(stage["global_start"]["diverged_evaluations"].get<int>(), 0);
  EXPECT_LT(stage["global_start"]["diverged_evaluations"].get<int>(),
            stage["global_start"]["evaluations"].get<int>());
  int checked = 0;
  for (const json& e : stage["estimates"]) {
    if (e["name"] == "T1") {
      EXPECT_NEAR(e["value"].get<double>(), 2.0875, 1e-3);
      ++checked;
    }
    if (e["name"] == "K") {
      EXPECT_NEAR(e["value"].get<double>(), -0.1724, 1e-4);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2);
}

TEST_F(DivergenceTest, DivergingStartStopsTheRunWithAMessageAndNoResults) {
  std::string messages;
  EXPECT_NE(folder_->Run("diverging_start.yaml", "diverging", &messages), 0);
  EXPECT_NE(messages.find("stage 'second_order'"), std::string::npos) << messages;
  EXPECT_NE(messages.find("diverges at the start values"), std::string::npos) << messages;
  EXPECT_FALSE(fs::exists(folder_->dir() / "diverging" / "results.json"));
  EXPECT_FALSE(fs::exists(folder_->dir() / "diverging" / "report.html"));
}

// Item 6 of the refinement issue: no finished work is thrown away. The run stops in the
// second stage with a message naming the experiment and time, and still writes the first
// stage's results, saying where it stopped.
TEST_F(DivergenceTest, StageThatDivergesKeepsTheFinishedStagesResults) {
  std::string messages;
  EXPECT_NE(folder_->Run("second_diverges.yaml", "second", &messages), 0);
  EXPECT_NE(messages.find("stopped in stage 'second'"), std::string::npos) << messages;
  EXPECT_NE(messages.find("experiment 'sine' diverges"), std::string::npos) << messages;
  EXPECT_NE(messages.find(" t = "), std::string::npos) << messages;
  const json results = Results("second");
  ASSERT_EQ(results["stages"].size(), 1u);
  EXPECT_EQ(results["stages"][0]["name"], "first");
  EXPECT_EQ(results["stopped"]["stage"], "second");
  ASSERT_FALSE(results["findings"].empty());
  EXPECT_EQ(results["findings"][0]["kind"], "run_stopped");
  EXPECT_EQ(results["findings"][0]["severity"], "failure");
  EXPECT_EQ(results["verdict"], "failed");
  EXPECT_NE(results["findings"][0]["message"].get<std::string>().find("stopped in stage 'second'"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(folder_->dir() / "second" / "report.html"));
  std::ifstream text(folder_->dir() / "second" / "report.txt");
  const std::string report((std::istreambuf_iterator<char>(text)),
                           std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("STOPPED in stage 'second'"), std::string::npos);
  // The final values are the first stage's.
  for (const json& p : results["parameters"]) {
    if (p["name"] == "T1") {
      EXPECT_NEAR(p["value"].get<double>(), 2.0875, 1e-3);
    }
  }
}

TEST_F(DivergenceTest, StudiesRecordDivergingCasesAndGoOn) {
  std::string messages;
  ASSERT_EQ(folder_->Study("global.yaml", "study", &messages), 0) << messages;
  const json study = folder_->Load("study");

  // Starts drawn in the bounds: some diverge at once and are recorded as failed with the
  // reason, the others are solved.
  int failed = 0, solved = 0;
  for (const json& c : study["starts"]["cases"]) {
    if (c["usable"].get<bool>()) {
      ++solved;
      continue;
    }
    ++failed;
    EXPECT_NE(c["message"].get<std::string>().find("diverges"), std::string::npos) << c.dump();
  }
  EXPECT_GT(failed, 0);
  EXPECT_GT(solved, 0);

  // The profile's held values below zero diverge: recorded, and the interval's lower end
  // says the profile could not be solved there.
  const json& profile = study["profile"]["stages"][0];
  int diverged = 0;
  for (const json& c : profile["cases"]) {
    if (c["usable"].get<bool>()) continue;
    ++diverged;
    EXPECT_NE(c["message"].get<std::string>().find("diverges"), std::string::npos) << c.dump();
  }
  EXPECT_GT(diverged, 0);
  EXPECT_TRUE(profile["profiles"][0]["lower"]["unsolved"].get<bool>());

  int usable_runs = 0;
  for (const json& c : study["monte_carlo"]["cases"]) usable_runs += c["usable"].get<bool>();
  EXPECT_EQ(usable_runs, 3) << study["monte_carlo"].dump();
}

}  // namespace divergence_test
}  // namespace vesselid

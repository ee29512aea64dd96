// `vesselid study` end to end on a small seed-000-like campaign (24 segments, 10 min): every
// split of the least-squares stage fitted, validation one-step R^2 high and stable over
// partitions, determinism over runs and thread counts, and config errors (an unknown stage,
// an unknown key) that leave no study.json. Then the output-error variant on a short seed-003
// patrol campaign (two 120 s records cut into 30 s segments): every split solved, fit and
// validation at the noise level, the same numbers on one thread and on two.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "engine/config/config.h"
#include "engine/study/partition_study.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/registry.h"
#include "tests/support/study_cli.h"
#include "yaml-cpp/yaml.h"

namespace vesselid {
namespace partition_study_test {

namespace fs = std::filesystem;
using nlohmann::json;

class PartitionStudy : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new testing::StudyFolder("vesselid_partition_study_test");
    // The shipped config on a smaller campaign, three partitions per method.
    YAML::Node config =
        YAML::LoadFile(std::string(VESSELID_SOURCE_DIR) + "/configs/input_gain_static.yaml");
    config["simulation"]["segments"] = 24;
    config["simulation"]["duration_min"] = 10;
    config["study"]["partitions"]["repetitions"] = 3;
    Write("study.yaml", config);
    config["study"] = YAML::Load("{partitions: {stage: nowhere}}");
    Write("unknown_stage.yaml", config);
    config["study"] = YAML::Load("{partitions: {repetitons: 3}}");
    Write("misspelt.yaml", config);
    Simulate("study.yaml");
    // The patrol vessel's multi-sine stage, the sine record added to its pool: 8 segments of
    // 30 s at 20 Hz, three partitions per method, shares 70 and 50 %. Identified from the
    // 50 % off starts without the global start (these starts do not need it).
    YAML::Node patrol = YAML::LoadFile(std::string(VESSELID_SOURCE_DIR) +
                                       "/configs/nomoto_patrol_noise.yaml");
    patrol["simulation"]["sample_time"] = 0.05;
    for (YAML::Node experiment : patrol["simulation"]["experiments"]) experiment["duration"] = 120;
    for (YAML::Node experiment : patrol["experiments"]) experiment["segment_length"] = 30;
    YAML::Node stage = YAML::Clone(patrol["stages"][1]);
    stage.remove("global");
    stage["free_initial_states"] = YAML::Load("[psi, xi1, xi2]");
    patrol["stages"] = YAML::Node(YAML::NodeType::Sequence);
    patrol["stages"].push_back(stage);
    patrol["study"] = YAML::Load(
        "{partitions: {stage: multisine, experiments: [sine], repetitions: 3, "
        "training_shares: [0.7, 0.5], methods: [segments, points]}}");
    Write("patrol.yaml", patrol);
    Simulate("patrol.yaml");
  }
  static void TearDownTestSuite() { delete folder_; }

  static void Write(const std::string& name, const YAML::Node& config) {
    folder_->Write(name, config);
  }
  static void Simulate(const std::string& config) { folder_->Simulate(config); }
  static int Study(const std::string& config, const std::string& out, std::string* messages,
                   const std::string& options = "") {
    return folder_->Study(config, out, messages, options);
  }

  // The partitions part of study.json.
  static json Load(const std::string& out) {
    const json j = folder_->Load(out);
    return j.is_object() && j.contains("partitions") ? j["partitions"] : json();
  }

  static testing::StudyFolder* folder_;
};

testing::StudyFolder* PartitionStudy::folder_ = nullptr;

TEST_F(PartitionStudy, EveryPartitionFitsAndPredictsTheHeldOutVelocities) {
  std::string messages;
  ASSERT_EQ(Study("study.yaml", "first", &messages), 0) << messages;
  EXPECT_TRUE(fs::exists(folder_->dir() / "first" / "study.txt"));
  const json j = Load("first");
  ASSERT_FALSE(j.is_discarded());
  EXPECT_EQ(j["stage"], "least_squares");
  EXPECT_EQ(j["pool"]["records"], 24);
  for (const std::string method : {"segments", "points"}) {
    SCOPED_TRACE(method);
    const json& m = j["repeated"][method];
    ASSERT_EQ(m["partitions"].size(), 3u);
    EXPECT_EQ(m["failed"], 0);
    for (const json& p : m["partitions"]) {
      EXPECT_TRUE(p["usable"].get<bool>()) << p["message"];
      for (const std::string state : {"u", "v", "r"}) {
        EXPECT_GT(p["validation"]["one_step"][state]["r2"].get<double>(), 0.95) << state;
      }
      if (method == "segments") {
        EXPECT_TRUE(p["validation"].contains("free_run"));
      }
    }
    for (const std::string state : {"u", "v", "r"}) {
      const json& r2 = m["summary"]["validation_one_step"][state]["r2"];
      EXPECT_EQ(r2["n"], 3);
      EXPECT_GT(r2["mean"].get<double>(), 0.95) << state;
      EXPECT_LT(r2["sd"].get<double>(), 0.05) << state;
    }
  }
  // Table (b): one split per training share and method.
  EXPECT_EQ(j["shares"].size(), 6u);
}

TEST_F(PartitionStudy, SameSeedGivesTheSameNumbers) {
  std::string messages;
  ASSERT_EQ(Study("study.yaml", "once", &messages), 0) << messages;
  ASSERT_EQ(Study("study.yaml", "twice", &messages), 0) << messages;
  EXPECT_EQ(testing::ComparableStudy(Load("once")), testing::ComparableStudy(Load("twice")));
}

TEST_F(PartitionStudy, ThreadCountDoesNotChangeTheNumbers) {
  std::string messages;
  ASSERT_EQ(Study("study.yaml", "one_thread", &messages, "--threads 1"), 0) << messages;
  ASSERT_EQ(Study("study.yaml", "two_threads", &messages, "--threads 2"), 0) << messages;
  const json one = testing::ComparableStudy(Load("one_thread"));
  EXPECT_EQ(one["repeated"]["segments"]["partitions"].size(), 3u);
  EXPECT_EQ(one, testing::ComparableStudy(Load("two_threads")));
}

TEST_F(PartitionStudy, UnknownStageIsRejectedWithoutWritingResults) {
  std::string messages;
  EXPECT_NE(Study("unknown_stage.yaml", "unknown_stage", &messages), 0);
  EXPECT_NE(messages.find("study.partitions.stage"), std::string::npos) << messages;
  EXPECT_NE(messages.find("no stage named 'nowhere'"), std::string::npos) << messages;
  EXPECT_FALSE(fs::exists(folder_->dir() / "unknown_stage" / "study.json"));
}

TEST_F(PartitionStudy, DefaultStageIsTheLastOutputErrorElseTheFirstLeastSquaresStage) {
  RunConfig config;
  std::string error;
  ASSERT_TRUE(LoadRunConfig((folder_->dir() / "study.yaml").string(), folder_->dir().string(), DefaultRegistry(),
                            &config, &error))
      << error;
  ASSERT_NE(PartitionStudyStage(config, ""), nullptr);
  EXPECT_EQ(PartitionStudyStage(config, "")->options.name, "refinement");
  EXPECT_EQ(PartitionStudyStage(config, "least_squares")->options.name, "least_squares");
  EXPECT_EQ(PartitionStudyStage(config, "nowhere"), nullptr);
  config.stages.pop_back();  // the run now ends with its least-squares stage
  ASSERT_NE(PartitionStudyStage(config, ""), nullptr);
  EXPECT_EQ(PartitionStudyStage(config, "")->options.name, "least_squares");
}

TEST_F(PartitionStudy, MisspeltKeyNamesTheStudySection) {
  RunConfig config;
  std::string error;
  EXPECT_FALSE(LoadRunConfig((folder_->dir() / "misspelt.yaml").string(), folder_->dir().string(), DefaultRegistry(),
                             &config, &error));
  EXPECT_NE(error.find("study"), std::string::npos) << error;
  EXPECT_NE(error.find("repetitons"), std::string::npos) << error;
}

// 0.1 deg of heading noise: the smallest RMSE a fit of the noisy heading can show.
constexpr double kHeadingNoise = 0.1 * M_PI / 180.0;

TEST_F(PartitionStudy, OutputErrorStageFitsAndValidatesEverySplit) {
  std::string messages;
  ASSERT_EQ(Study("patrol.yaml", "patrol", &messages), 0) << messages;
  const json j = Load("patrol");
  ASSERT_FALSE(j.is_discarded());
  EXPECT_EQ(j["stage"], "multisine");
  EXPECT_EQ(j["kind"], "output_error");
  EXPECT_EQ(j["outputs"], json::array({"psi"}));
  EXPECT_EQ(j["options"]["experiments"], json::array({"multisine", "sine"}));
  ASSERT_EQ(j["pool"]["experiments"], 8);  // 2 records x 4 segments of 30 s
  const int samples = j["pool"]["samples"];
  EXPECT_GT(samples, 4000);
  // A split's fit and validation are at the noise level: the model explains the rest.
  auto expect_noise_level = [](const json& psi, const std::string& part) {
    SCOPED_TRACE(part);
    EXPECT_GT(psi["samples"].get<int>(), 0);
    EXPECT_GT(psi["rmse"].get<double>(), 0.8 * kHeadingNoise);
    EXPECT_LT(psi["rmse"].get<double>(), 1.5 * kHeadingNoise);
    EXPECT_LT(psi["mae"].get<double>(), psi["rmse"].get<double>());
    EXPECT_GT(psi["r2"].get<double>(), 0.999);
    EXPECT_GT(psi["fit_percent"].get<double>(), 95.0);
  };
  for (const std::string method : {"segments", "points"}) {
    SCOPED_TRACE(method);
    const json& m = j["repeated"][method];
    ASSERT_EQ(m["partitions"].size(), 3u);
    EXPECT_EQ(m["failed"], 0);
    for (const json& p : m["partitions"]) {
      ASSERT_TRUE(p["usable"].get<bool>()) << p["message"];
      EXPECT_EQ(p["message"], "");
      expect_noise_level(p["training"]["fit"]["psi"], "training");
      expect_noise_level(p["validation"]["free_run"]["psi"], "validation");
      EXPECT_GT(p["training"]["cost"].get<double>(), 0.0);
      if (method == "segments") {  // 30 % of 8 segments held out, the rest trained on
        EXPECT_EQ(p["validation"]["experiments"], 2);
        EXPECT_EQ(p["training"]["experiments"], 6);
      } else {  // 30 % of the samples held out, every segment keeps some of both
        EXPECT_EQ(p["validation"]["samples"], std::lround(0.3 * samples));
        EXPECT_EQ(p["training"]["samples"], samples - std::lround(0.3 * samples));
        EXPECT_EQ(p["training"]["experiments"], 8);
        EXPECT_EQ(p["validation"]["experiments"], 8);
      }
      EXPECT_EQ(p["validation"]["free_run"]["psi"]["samples"], p["validation"]["samples"]);
    }
    const json& summary = m["summary"];
    EXPECT_EQ(summary["validation_free_run"]["psi"]["rmse"]["n"], 3);
    EXPECT_LT(summary["validation_free_run"]["psi"]["rmse"]["mean"].get<double>(),
              1.5 * kHeadingNoise);
    // The gain is determined by every partition alike; delta_0 is held.
    const json& k = summary["parameters"]["K"];
    EXPECT_EQ(k["n"], 3);
    EXPECT_LT(k["sd"].get<double>(), 0.01 * std::abs(k["mean"].get<double>()));
  }
  EXPECT_EQ(j["parameters"][4], json({{"name", "delta_0"}, {"held", true}}));
  // Table (b): shares 70 and 50 % per method, every split usable.
  ASSERT_EQ(j["shares"].size(), 4u);
  for (const json& b : j["shares"]) EXPECT_TRUE(b["usable"].get<bool>()) << b["message"];
  std::ifstream text(folder_->dir() / "patrol" / "study.txt");
  const std::string report((std::istreambuf_iterator<char>(text)),
                           std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("output-error stage 'multisine'"), std::string::npos) << report;
  EXPECT_NE(report.find("fit %"), std::string::npos) << report;
}

TEST_F(PartitionStudy, OutputErrorNumbersDoNotDependOnTheThreadCount) {
  std::string messages;
  ASSERT_EQ(Study("patrol.yaml", "patrol_one", &messages, "--threads 1"), 0) << messages;
  ASSERT_EQ(Study("patrol.yaml", "patrol_two", &messages, "--threads 2"), 0) << messages;
  const json one = testing::ComparableStudy(Load("patrol_one"));
  EXPECT_EQ(one["repeated"]["points"]["failed"], 0);
  EXPECT_EQ(one, testing::ComparableStudy(Load("patrol_two")));
}

TEST(StudyOptions, SharesMustFitTheData) {
  StudyOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error)) << error;
  options.training_shares = {0.8};
  EXPECT_FALSE(options.IsValid(&error));
  options.training_shares = {0.7};
  options.methods = {"samples"};
  EXPECT_FALSE(options.IsValid(&error));
  options.methods = {"points"};
  options.partitions = 0;
  EXPECT_FALSE(options.IsValid(&error));
}

}  // namespace partition_study_test
}  // namespace vesselid

// `vesselid study` end to end on a small seed-000-like campaign (24 segments, 10 min): every
// split fitted, validation one-step R^2 high and stable over partitions, determinism, and
// config errors (an output-error stage, an unknown key) that leave no study.json.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "engine/config.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/registry.h"
#include "yaml-cpp/yaml.h"

namespace vesselid {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class PartitionStudy : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per process: CTest runs tests in parallel processes.
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_partition_study_test_" + std::to_string(getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    // The shipped config on a smaller campaign, three partitions per method.
    YAML::Node config =
        YAML::LoadFile(std::string(VESSELID_SOURCE_DIR) + "/configs/input_gain_static.yaml");
    config["simulation"]["segments"] = 24;
    config["simulation"]["duration_min"] = 10;
    config["study"]["partitions"]["repetitions"] = 3;
    Write("study.yaml", config);
    config["study"] = YAML::Load("{partitions: {stage: refinement}}");
    Write("refinement.yaml", config);
    config["study"] = YAML::Load("{partitions: {repetitons: 3}}");
    Write("misspelt.yaml", config);
    const std::string simulate = std::string(VESSELID_BINARY) + " simulate " +
                                 (*dir_ / "study.yaml").string() + " --out " + dir_->string() +
                                 " > /dev/null";
    ASSERT_EQ(std::system(simulate.c_str()), 0) << simulate;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  static void Write(const std::string& name, const YAML::Node& config) {
    YAML::Emitter out;
    out << config;
    std::ofstream(*dir_ / name) << out.c_str() << "\n";
  }

  // Runs `vesselid study` on `config` into `out`; its exit status and stderr.
  static int Study(const std::string& config, const std::string& out, std::string* messages) {
    const fs::path log = *dir_ / (out + ".stderr");
    const std::string command = std::string(VESSELID_BINARY) + " study " +
                                (*dir_ / config).string() + " --data " + dir_->string() +
                                " --out " + (*dir_ / out).string() + " --quiet > /dev/null 2> " +
                                log.string();
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    messages->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return status;
  }

  // The partitions part of study.json.
  static json Load(const std::string& out) {
    std::ifstream in(*dir_ / out / "study.json");
    EXPECT_TRUE(in.good()) << "no study.json in " << out;
    const json j = json::parse(in, nullptr, /*allow_exceptions=*/false);
    return j.is_object() && j.contains("partitions") ? j["partitions"] : json();
  }

  // The JSON without its timings, for comparing runs.
  static json WithoutTimes(json j) {
    if (j.is_object()) {
      j.erase("time_seconds");
      for (auto& item : j.items()) item.value() = WithoutTimes(item.value());
    } else if (j.is_array()) {
      for (auto& item : j) item = WithoutTimes(item);
    }
    return j;
  }

  static fs::path* dir_;
};

fs::path* PartitionStudy::dir_ = nullptr;

TEST_F(PartitionStudy, EveryPartitionFitsAndPredictsTheHeldOutVelocities) {
  std::string messages;
  ASSERT_EQ(Study("study.yaml", "first", &messages), 0) << messages;
  EXPECT_TRUE(fs::exists(*dir_ / "first" / "study.txt"));
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
  EXPECT_EQ(WithoutTimes(Load("once")), WithoutTimes(Load("twice")));
}

TEST_F(PartitionStudy, OutputErrorStageIsRejectedWithoutWritingResults) {
  std::string messages;
  EXPECT_NE(Study("refinement.yaml", "refinement", &messages), 0);
  EXPECT_NE(messages.find("study.partitions.stage"), std::string::npos) << messages;
  EXPECT_NE(messages.find("not a least_squares stage"), std::string::npos) << messages;
  EXPECT_FALSE(fs::exists(*dir_ / "refinement" / "study.json"));
}

TEST_F(PartitionStudy, MisspeltKeyNamesTheStudySection) {
  RunConfig config;
  std::string error;
  EXPECT_FALSE(LoadRunConfig((*dir_ / "misspelt.yaml").string(), dir_->string(), DefaultRegistry(),
                             &config, &error));
  EXPECT_NE(error.find("study"), std::string::npos) << error;
  EXPECT_NE(error.find("repetitons"), std::string::npos) << error;
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

}  // namespace
}  // namespace vesselid

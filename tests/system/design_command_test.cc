// `vesselid design` through the command line, as a user runs it (configs/design_patrol.yaml):
// simulate, run, then plan. The plan shrinks every standard error, keeps its limits and
// writes its whole set; a bad design section is refused naming file, line and key, with
// nothing written. The sanitized suite reaches the design command's code paths here
// (docs/development.md, "What runs sanitized"); tests/python/test_design.py checks the plan's
// figures and the closed loop.
#include <filesystem>
#include <fstream>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/run_command.h"

namespace vesselid {
namespace design_command_test {

namespace fs = std::filesystem;

const std::string kBinary = VESSELID_BINARY;
const std::string kConfig = std::string(VESSELID_SOURCE_DIR) + "/configs/design_patrol.yaml";

// Simulates and runs the patrol vessel's short zigzag into dir/data and dir/run.
void SimulateAndRun(const fs::path& dir) {
  fs::remove_all(dir);
  testing::CommandOutcome outcome =
      testing::RunCommand(kBinary + " simulate " + kConfig + " --out " + (dir / "data").string());
  ASSERT_EQ(outcome.status, 0) << outcome.output;
  outcome = testing::RunCommand(kBinary + " run " + kConfig + " --data " + (dir / "data").string() +
                                " --out " + (dir / "run").string() + " --quiet --no-report");
  ASSERT_EQ(outcome.status, 0) << outcome.output;
}

TEST(DesignCommand, PlansWithinItsLimitsAndShrinksEveryStandardError) {
  const fs::path dir = fs::temp_directory_path() / "vesselid_design_command";
  ASSERT_NO_FATAL_FAILURE(SimulateAndRun(dir));
  const testing::CommandOutcome outcome = testing::RunCommand(
      kBinary + " design " + kConfig + " --from " + (dir / "run").string() + " --quiet");
  ASSERT_EQ(outcome.status, 0) << outcome.output;
  for (const char* file :
       {"design.json", "design.txt", "planned_input.csv", "predicted.csv", "report.html"}) {
    EXPECT_TRUE(fs::exists(dir / "run" / "design" / file)) << file;
  }
  std::ifstream in(dir / "run" / "design" / "design.json");
  const nlohmann::json design = nlohmann::json::parse(in);
  EXPECT_TRUE(design["limits"]["respected"].get<bool>());
  const nlohmann::json& errors = design["predicted_std_errors"];
  for (const char* parameter : {"T1", "T2", "T3", "K"}) {
    ASSERT_TRUE(errors["current"][parameter].is_number()) << parameter;
    ASSERT_TRUE(errors["planned"][parameter].is_number()) << parameter;
    EXPECT_LT(errors["planned"][parameter].get<double>(),
              errors["current"][parameter].get<double>())
        << parameter;
  }
  for (const char* alternative : {"zigzag_10_10", "zigzag_20_20", "spiral", "multisine", "prbs"}) {
    EXPECT_TRUE(errors["alternatives"].contains(alternative)) << alternative;
  }
}

TEST(DesignCommand, BadSectionIsRefusedNamingFileLineAndKeyWithNothingWritten) {
  const fs::path dir = fs::temp_directory_path() / "vesselid_design_command_bad";
  ASSERT_NO_FATAL_FAILURE(SimulateAndRun(dir));
  std::ifstream in(kConfig);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string key = "  criterion: D";
  const size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, key.size(), "  criterion: F");
  const fs::path bad = dir / "design_bad.yaml";
  std::ofstream(bad) << text;
  const testing::CommandOutcome outcome = testing::RunCommand(kBinary + " design " + bad.string() +
                                                              " --from " + (dir / "run").string());
  EXPECT_NE(outcome.status, 0);
  EXPECT_NE(outcome.output.find("design_bad.yaml:"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("design.criterion"), std::string::npos) << outcome.output;
  EXPECT_FALSE(fs::exists(dir / "run" / "design")) << outcome.output;
}

}  // namespace design_command_test
}  // namespace vesselid

// What `vesselid run` prints while it works: a line per stage when stderr is not a terminal
// (CI logs), a live status line on a terminal, every iteration with --verbose, nothing with
// --quiet.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "gtest/gtest.h"
#include "tests/support/patrol_config.h"
#include "tests/support/study_cli.h"

namespace vesselid {
namespace progress_test {

namespace fs = std::filesystem;

std::string ConfigText() {
  return testing::PatrolConfigHead(120) + R"(
stages:
  - name: gain
    parameters:
      K: {start: -0.11, lower: -2.0, upper: -0.001}
  - name: all
    parameters:
      T1: {start: 3.0, lower: 0.01, upper: 20.0}
      T2: {start: 0.2, lower: 0.01, upper: 20.0}
      T3: {start: 0.27, lower: 0.0, upper: 5.0}
      K: {lower: -2.0, upper: -0.001}
    global: {algorithm: GN_CRS2_LM, max_evaluations: 100, seed: 1}
)";
}

class ProgressTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new testing::StudyFolder("vesselid_progress");
    std::ofstream(folder_->dir() / "two_stages.yaml") << ConfigText();
    folder_->Simulate("two_stages.yaml");
  }
  static void TearDownTestSuite() { delete folder_; }

  // Runs `vesselid run` with `options`, stdout and stderr apart; `wrap` turns the command
  // into another (a terminal around it). Returns the exit status.
  static int Run(const std::string& options, std::string* out, std::string* err,
                 const std::string& wrap = "") {
    const fs::path dir = folder_->dir();
    std::string command = std::string(VESSELID_BINARY) + " run " +
                          (dir / "two_stages.yaml").string() + " --data " + dir.string() +
                          " --out " + (dir / "out").string() + " " + options;
    if (!wrap.empty()) command = wrap + " '" + command + "' /dev/null";
    command += " > " + (dir / "stdout").string() + " 2> " + (dir / "stderr").string();
    const int status = std::system(command.c_str());
    *out = Read(dir / "stdout");
    *err = Read(dir / "stderr");
    return status;
  }

  static std::string Read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

  static std::vector<std::string> Lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  static testing::StudyFolder* folder_;
};

testing::StudyFolder* ProgressTest::folder_ = nullptr;

TEST_F(ProgressTest, NotOnATerminalOneLinePerStage) {
  std::string out, err;
  ASSERT_EQ(Run("", &out, &err), 0) << err;
  std::vector<std::string> lines = Lines(err);
  // After the stage lines, the run's findings: the gain-only stage fits the data poorly (20 %)
  // and leaves strong structure in its residuals; the verdict last, the last stage's (the gain
  // stage was a start).
  ASSERT_EQ(lines.size(), 5u) << err;
  EXPECT_EQ(lines[2].rfind("vesselid: warning [poor_fit] stage 'gain', experiment 'sine', output "
                           "psi: the simulated psi explains less than half of its record",
                           0),
            0u)
      << lines[2];
  EXPECT_EQ(lines[3].rfind("vesselid: warning [coloured_residuals] stage 'gain', output psi:", 0),
            0u)
      << lines[3];
  EXPECT_EQ(lines[4].rfind("vesselid: verdict: good (0 failure(s), 2 warning(s)", 0), 0u)
      << lines[4];
  EXPECT_TRUE(std::regex_match(lines[0], std::regex(R"(\[1/2\] stage gain: cost .* s)")))
      << lines[0];
  EXPECT_TRUE(std::regex_match(lines[1], std::regex(R"(\[2/2\] stage all: cost .* s)")))
      << lines[1];
  EXPECT_EQ(err.find('\r'), std::string::npos);
  EXPECT_NE(out.find("results written to"), std::string::npos);
}

TEST_F(ProgressTest, QuietPrintsOnlyTheResultsPath) {
  std::string out, err;
  ASSERT_EQ(Run("--quiet", &out, &err), 0) << err;
  // Failures and warnings are never silenced, nor is the verdict.
  EXPECT_EQ(Lines(err).size(), 3u) << err;
  EXPECT_EQ(err.rfind("vesselid: warning [poor_fit] stage 'gain'", 0), 0u) << err;
  EXPECT_EQ(Lines(out).size(), 1u) << out;  // the path alone
}

TEST_F(ProgressTest, VerboseShowsEveryPhaseAndIteration) {
  std::string out, err;
  ASSERT_EQ(Run("--verbose", &out, &err), 0) << err;
  EXPECT_NE(err.find("[1/2] stage gain: running"), std::string::npos) << err;
  EXPECT_NE(err.find("[1/2] stage gain: local refinement 1/1, iteration 1, cost"),
            std::string::npos) << err;
  EXPECT_NE(err.find("[2/2] stage all: global search, evaluation 1, best cost"),
            std::string::npos) << err;
  EXPECT_NE(err.find("[2/2] stage all: local refinement 2/"), std::string::npos) << err;
}

TEST_F(ProgressTest, QuietAndVerboseExcludeEachOther) {
  std::string out, err;
  EXPECT_NE(Run("--quiet --verbose", &out, &err), 0);
  EXPECT_NE(err.find("excludes"), std::string::npos) << err;
}

// On a terminal (util-linux `script` gives the run one): the status line is rewritten in
// place with the phase, iteration and cost, then replaced by the stage's line.
TEST_F(ProgressTest, OnATerminalALiveStatusLine) {
  std::string out, err;
  ASSERT_EQ(Run("", &out, &err, "script -qec"), 0) << out << err;
  EXPECT_NE(out.find("\r\033[K[1/2] stage gain: cost"), std::string::npos) << out;
  EXPECT_NE(out.find("[2/2] stage all: "), std::string::npos) << out;
  EXPECT_NE(out.find("[2/2] stage all: cost"), std::string::npos) << out;
}

}  // namespace progress_test
}  // namespace vesselid

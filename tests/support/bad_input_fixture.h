// The command-line fixture of the bad- and hostile-input tests: a folder with a small Nomoto
// record (data.csv) and a config that identifies it (config.yaml), edited by each case, and
// `vesselid run` on them.
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "engine/data/trajectory.h"
#include "gtest/gtest.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"

namespace vesselid::testing {

namespace fs = std::filesystem;

inline constexpr char kGoodConfig[] = R"(model: {family: nomoto, type: first_order}
experiments:
  - name: run
    file: data.csv
    inputs: {delta: delta}
    outputs: {psi: psi}
stages:
  - name: fit
    parameters:
      T: {start: 3.0, lower: 0.1, upper: 50.0}
      K: {start: -0.1, lower: -1.0, upper: -0.001}
    free_initial_states: [psi]
)";

struct Outcome {
  int status;
  std::string output;
};

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    // Suite and test name: BadInput and BadSpeedInput (two programs ctest may run at once)
    // share test names.
    const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("vesselid_bad_input_" + std::string(test->test_suite_name()) + "_" + test->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    auto model = nomoto::MakeFirstOrderHandle();
    nomoto::ClosedLoopOptions loop;
    loop.duration = RecordSeconds();
    loop.sample_time = 0.1;
    loop.controller_gain = 0.7;
    loop.excitation.amplitude = 0.3;
    loop.excitation.periods = {20.0};
    Trajectory data;
    std::string error;
    ASSERT_TRUE(nomoto::SimulateClosedLoop(*model, {2.0, -0.17, 0.0}, loop, &data, &error));
    ASSERT_TRUE(WriteTrajectoryCsv((dir_ / "data.csv").string(), data, &error));
    WriteConfig(kGoodConfig);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // The length of data.csv (0.1 s samples).
  virtual double RecordSeconds() const { return 60.0; }

  void WriteConfig(const std::string& text) { std::ofstream(dir_ / "config.yaml") << text; }

  // Replaces the first occurrence of `from` in the good config.
  void EditConfig(const std::string& from, const std::string& to) {
    std::string text = kGoodConfig;
    size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    WriteConfig(text.replace(at, from.size(), to));
  }

  // Rewrites data line `line` (1-based, header is 1) with `text`.
  void EditDataLine(int line, const std::string& text) {
    std::ifstream in(dir_ / "data.csv");
    std::string all, row;
    for (int n = 1; std::getline(in, row); ++n) all += (n == line ? text : row) + "\n";
    std::ofstream(dir_ / "data.csv") << all;
  }

  // `vesselid run config.yaml --out <out>`, after `shell` (e.g. "ulimit -f 64;").
  Outcome Run(const std::string& shell = "", const fs::path& out = "") {
    const std::string command = shell + std::string(VESSELID_BINARY) + " run " +
                                (dir_ / "config.yaml").string() + " --out " +
                                (out.empty() ? dir_ / "out" : out).string() + " 2>&1";
    Outcome outcome{0, ""};
    FILE* pipe = popen(command.c_str(), "r");
    char buffer[512];
    while (fgets(buffer, sizeof(buffer), pipe) != nullptr) outcome.output += buffer;
    outcome.status = pclose(pipe);
    return outcome;
  }

  // Runs and checks: failure, the message matches `pattern`, no results and no temporary file
  // written.
  Outcome ExpectRejected(const std::string& pattern, const std::string& shell = "",
                         const fs::path& out = "") {
    Outcome outcome = Run(shell, out);
    EXPECT_NE(outcome.status, 0) << outcome.output;
    EXPECT_TRUE(std::regex_search(outcome.output, std::regex(pattern)))
        << "message: " << outcome.output << "expected pattern: " << pattern;
    const fs::path folder = out.empty() ? dir_ / "out" : out;
    std::error_code ec;
    EXPECT_FALSE(fs::exists(folder / "results.json", ec));
    if (fs::is_directory(folder, ec)) {
      for (const auto& entry : fs::recursive_directory_iterator(folder, ec)) {
        EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
      }
    }
    return outcome;
  }

  fs::path dir_;
};

}  // namespace vesselid::testing

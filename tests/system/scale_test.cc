// Campaigns at scale through the command line: a config of 10 000 experiments cut from one log
// is read in memory proportional to it (experiment_defaults merged into each, the log read and
// its fingerprint hashed once) and runs to the end within the memory budget, its shared
// parameters with standard errors (the covariance by blocks). The peak is measured with
// getrusage. A log cut into segments by its segment column: 50 000 run within a budget of
// 1 GiB, each segment's results counted before the first stage; 500 000 under a budget of
// 2 GiB are refused before any stage, saying what they need. Label long: the 10 000
// experiments take two minutes.
#include <sys/resource.h>

#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "engine/data/trajectory.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"

namespace vesselid {
namespace scale_test {

namespace fs = std::filesystem;

constexpr int kExperiments = 10000;
constexpr double kWindow = 10.0;  // s, each experiment's window of the log

// Largest resident set of any child process so far, MiB.
double ChildPeakMiB() {
  struct rusage usage;
  ::getrusage(RUSAGE_CHILDREN, &usage);
  return usage.ru_maxrss / 1024.0;
}

int RunCommand(const std::string& command, std::string* output) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe) != nullptr) *output += buffer;
  return pclose(pipe);
}

// A first-order Nomoto ship (T 2 s, K -0.17 1/s) under a heading controller, logged at 10 Hz
// for `duration` seconds into `dir` (emptied first).
void SimulateLog(const fs::path& dir, double duration, Trajectory* data) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto model = nomoto::MakeFirstOrderHandle();
  nomoto::ClosedLoopOptions loop;
  loop.duration = duration;
  loop.sample_time = 0.1;
  loop.controller_gain = 0.7;
  loop.excitation.amplitude = 0.3;
  loop.excitation.periods = {20.0};
  std::string error;
  ASSERT_TRUE(nomoto::SimulateClosedLoop(*model, {2.0, -0.17, 0.0}, loop, data, &error)) << error;
}

TEST(Scale, TenThousandWindowsOfOneLogRunWithinTheBudget) {
  const fs::path dir = fs::temp_directory_path() / "vesselid_scale_windows";
  // One log of the whole campaign.
  Trajectory data;
  SimulateLog(dir, kExperiments * kWindow, &data);
  std::string error;
  ASSERT_TRUE(WriteTrajectoryCsv((dir / "log.csv").string(), data, &error)) << error;
  std::ofstream config(dir / "config.yaml");
  config << "model: {family: nomoto, type: first_order}\n"
            "experiment_defaults: {file: log.csv, inputs: {delta: delta}, outputs: {psi: psi}}\n"
            "experiments:\n";
  for (int i = 0; i < kExperiments; ++i) {
    config << "  - {name: w" << i << ", window: [" << i * kWindow << ", " << (i + 1) * kWindow
           << "]}\n";
  }
  config << "stages:\n"
            "  - name: fit\n"
            "    free_initial_states: [psi, r]\n"  // 20 002 free variables: by blocks
            "    parameters:\n"
            "      T: {start: 3.0, lower: 0.1, upper: 50.0}\n"
            "      K: {start: -0.1, lower: -1.0, upper: -0.001}\n";
  config.close();

  const auto start = std::chrono::steady_clock::now();
  std::string output;
  const int status =
      RunCommand(std::string(VESSELID_BINARY) + " run " + (dir / "config.yaml").string() +
                     " --out " + (dir / "out").string() + " --quiet --no-report",
                 &output);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(status, 0) << output.substr(0, 4000);
  std::printf("10 000 experiments: %.0f s, peak %.0f MiB\n", seconds, ChildPeakMiB());
  // The log is 100 000 s at 10 Hz (1e6 rows, 24 MiB as doubles); the run holds it once.
  EXPECT_LT(ChildPeakMiB(), 1024.0);
  std::ifstream in(dir / "out" / "results.json");
  const nlohmann::json results = nlohmann::json::parse(in);
  std::map<std::string, double> value, std_error;
  for (const nlohmann::json& p : results["parameters"]) {
    value[p["name"]] = p["value"].get<double>();
    if (p["std_error"].is_number()) std_error[p["name"]] = p["std_error"].get<double>();
  }
  EXPECT_NEAR(value["T"], 2.0, 0.05);
  EXPECT_NEAR(value["K"], -0.17, 0.005);
  // The shared parameters keep their standard errors (the covariance by blocks); the data
  // are noise-free, so they are small, but known.
  EXPECT_TRUE(std_error.count("T") && std_error["T"] >= 0.0 && std_error["T"] < 0.05);
  EXPECT_TRUE(std_error.count("K") && std_error["K"] >= 0.0 && std_error["K"] < 0.005);
  fs::remove_all(dir);
}

// A first-order Nomoto log of `segments` segments of `rows` samples (10 Hz) with their ids in
// the column `segment`, and a config fitting T and K over them (each segment's psi and r free).
void WriteSegmentedCampaign(const fs::path& dir, int segments, int rows, int memory_mb) {
  Trajectory data;
  SimulateLog(dir, segments * rows * 0.1, &data);
  std::string error;
  data.t.resize(static_cast<size_t>(segments) * rows);
  for (std::vector<double>& column : data.columns) column.resize(data.t.size());
  std::vector<double> segment(data.t.size());
  for (size_t k = 0; k < segment.size(); ++k) segment[k] = static_cast<double>(k / rows);
  data.names.push_back("segment");
  data.columns.push_back(std::move(segment));
  ASSERT_TRUE(WriteTrajectoryCsv((dir / "log.csv").string(), data, &error)) << error;
  std::ofstream(dir / "config.yaml")
      << "model: {family: nomoto, type: first_order}\n"
         "limits: {memory_mb: " << memory_mb << "}\n"
         "experiments:\n"
         "  - {name: log, file: log.csv, inputs: {delta: delta}, outputs: {psi: psi},\n"
         "     segments: {column: segment}}\n"
         "stages:\n"
         "  - name: fit\n"
         "    free_initial_states: [psi, r]\n"
         "    parameters:\n"
         "      T: {start: 3.0, lower: 0.1, upper: 50.0}\n"
         "      K: {start: -0.1, lower: -1.0, upper: -0.001}\n";
}

int RunCampaign(const fs::path& dir, std::string* output) {
  return RunCommand(std::string(VESSELID_BINARY) + " run " + (dir / "config.yaml").string() +
                        " --out " + (dir / "out").string() + " --quiet --no-report",
                    output);
}

TEST(Scale, FiftyThousandSegmentsRunWithinTheirBudget) {
  const fs::path dir = fs::temp_directory_path() / "vesselid_scale_segments";
  WriteSegmentedCampaign(dir, 50000, 20, 1024);
  std::string output;
  const int status = RunCampaign(dir, &output);
  std::printf("50 000 segments: peak %.0f MiB\n", ChildPeakMiB());
  ASSERT_EQ(status, 0) << output.substr(0, 4000);
  EXPECT_LT(ChildPeakMiB(), 1.1 * 1024.0);
  std::ifstream in(dir / "out" / "results.json");
  const nlohmann::json results = nlohmann::json::parse(in);
  std::map<std::string, double> value;
  for (const nlohmann::json& p : results["parameters"]) {
    value[p["name"]] = p["value"].get<double>();
  }
  EXPECT_NEAR(value["T"], 2.0, 0.05);
  EXPECT_NEAR(value["K"], -0.17, 0.005);
  // One trace for the log, its segments one after another.
  EXPECT_TRUE(fs::exists(dir / "out" / "traces" / "fit.log.csv"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "out" / "traces"), {}), 1);
  fs::remove_all(dir);
}

TEST(Scale, HalfAMillionSegmentsOverTheBudgetAreRefusedBeforeTheFirstStage) {
  const fs::path dir = fs::temp_directory_path() / "vesselid_scale_many_segments";
  WriteSegmentedCampaign(dir, 500000, 8, 2048);
  std::string output;
  const int status = RunCampaign(dir, &output);
  std::printf("500 000 segments: peak %.0f MiB\n%s\n", ChildPeakMiB(), output.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << output.substr(0, 4000);
  EXPECT_EQ(WEXITSTATUS(status), 1) << output.substr(0, 4000);
  EXPECT_LT(ChildPeakMiB(), 1.1 * 2048.0);
  EXPECT_NE(output.find("stage 'fit': its experiments need"), std::string::npos) << output;
  EXPECT_NE(output.find("the results of 5e+05 experiments and segments"), std::string::npos)
      << output;
  EXPECT_NE(output.find("limits.memory_mb"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(dir / "out" / "results.json"));
  EXPECT_FALSE(fs::exists(dir / "out" / ".vesselid-checkpoint" / "stage_001.cbor"));
  EXPECT_FALSE(fs::exists(dir / "out" / "checkpoint"));
  fs::remove_all(dir);
}

}  // namespace scale_test
}  // namespace vesselid

// Runs a shipped config end to end through the command line, as a user would:
// `vesselid simulate configs/<name>.yaml`, then `vesselid run` on the simulated data.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"

namespace vesselid::testing {

// Writes `config` as <dir>/<name>.yaml and runs it on the data in `dir` into <dir>/<name>;
// expects exit 0 and returns results.json (discarded when missing).
inline nlohmann::json RunConfigOn(const std::filesystem::path& dir, const std::string& name,
                                  const std::string& config) {
  const std::filesystem::path file = dir / (name + ".yaml");
  std::ofstream(file) << config;
  const std::filesystem::path out = dir / name;
  const std::string run = std::string(VESSELID_BINARY) + " run " + file.string() + " --data " +
                          dir.string() + " --out " + out.string() + " --quiet > /dev/null 2>&1";
  EXPECT_EQ(std::system(run.c_str()), 0) << run;
  std::ifstream in(out / "results.json");
  return nlohmann::json::parse(in, nullptr, false);
}

struct ShippedRun {
  nlohmann::json results;  // results.json
  std::string report;      // report.txt
};

// Simulates and runs configs/<name>.yaml into `out` (data and results side by side).
inline void SimulateAndRunInto(const std::string& name, const std::filesystem::path& out) {
  const std::string config = std::string(VESSELID_SOURCE_DIR) + "/configs/" + name + ".yaml";
  std::filesystem::remove_all(out);
  const std::string binary = VESSELID_BINARY;
  const std::string simulate =
      binary + " simulate " + config + " --out " + out.string() + " > /dev/null";
  const std::string run = binary + " run " + config + " --data " + out.string() + " --out " +
                          out.string() + " --quiet > /dev/null";
  ASSERT_EQ(std::system(simulate.c_str()), 0) << simulate;
  ASSERT_EQ(std::system(run.c_str()), 0) << run;
}

inline ShippedRun SimulateAndRun(const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path out = fs::temp_directory_path() / ("vesselid_shipped_config_" + name);
  SimulateAndRunInto(name, out);
  ShippedRun result;
  std::ifstream in(out / "results.json");
  result.results = nlohmann::json::parse(in);
  std::ifstream report(out / "report.txt");
  EXPECT_TRUE(report.good()) << "no report.txt";
  result.report.assign(std::istreambuf_iterator<char>(report), std::istreambuf_iterator<char>());
  fs::remove_all(out);
  return result;
}

}  // namespace vesselid::testing

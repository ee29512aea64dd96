// The same results on any number of threads, and `vesselid run --no-report`.
//
// A multi-experiment stage on data the identified model did not make: the shipped tanker
// campaign (configs/nomoto_tanker.yaml: a Norrbin ship with a steering-gear rate limit, a slow
// yaw disturbance and a quantised compass, logged in degrees) cut to four training runs and
// two held-out runs, run with `local: {num_threads: 1}`, 2 and 3 (more threads than this
// machine's cores included), and once with num_threads absent (the machine's cores). Ceres
// evaluates the experiments' residual blocks on its threads, the held-out runs are fitted and
// their velocities measured in parallel; results.json must be the same bit for bit, timings apart.
//
// Ceres 2.1 sums the cost and gradient per thread and then over threads, so the thread count
// changes the last bits of the costs it reports (found here: the cost, the residual variance
// and with them every standard error differed in the 16th digit). The engine therefore
// reports costs summed in the problem's own order (local_solve.cc) and evaluates the
// Jacobian of the HAC covariance and the local analysis on one thread (stage.cc); the steps
// come from the Jacobian and residuals each block writes into its own place. Should a Ceres
// version still make this fail, its step acceptance on a cost a few ulps apart is the cause.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/results_json_times.h"
#include "yaml-cpp/yaml.h"

namespace vesselid {
namespace thread_count_test {

using nlohmann::json;
using testing::DropTimes;
namespace fs = std::filesystem;

// Where a and b differ ("/stages/1/cost: 0.1 vs 0.1000001"), at most `limit` places.
void Differences(const json& a, const json& b, const std::string& at, std::string* out,
                 int* limit) {
  if (*limit <= 0 || a == b) return;
  if (a.is_object() && b.is_object()) {
    for (const auto& [key, value] : a.items()) {
      Differences(value, b.contains(key) ? b[key] : json(), at + "/" + key, out, limit);
    }
    for (const auto& [key, value] : b.items()) {
      if (!a.contains(key)) Differences(json(), value, at + "/" + key, out, limit);
    }
  } else if (a.is_array() && b.is_array() && a.size() == b.size()) {
    for (size_t i = 0; i < a.size(); ++i) {
      Differences(a[i], b[i], at + "/" + std::to_string(i), out, limit);
    }
  } else {
    const std::string left = a.dump(), right = b.dump();
    *out += at + ": " + left.substr(0, 400) + " vs " + right.substr(0, 400) + "\n";
    --*limit;
  }
}

std::string Differences(const json& a, const json& b) {
  std::string out;
  int limit = 12;
  Differences(a, b, "", &out, &limit);
  return out;
}

class ThreadCount : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_thread_count_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    const std::string shipped = std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_tanker.yaml";
    const std::string simulate = std::string(VESSELID_BINARY) + " simulate " + shipped +
                                 " --out " + dir_->string() + " > /dev/null";
    simulated_ = std::system(simulate.c_str()) == 0;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }

  // The tanker config cut to four training and two held-out runs; `threads` < 0: no
  // num_threads key. Returns the process's exit status; results in <dir>/<name>.
  static int Run(const std::string& name, int threads, const std::string& flags = "",
                 int global_threads = -1) {
    YAML::Node config =
        YAML::LoadFile(std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_tanker.yaml");
    config.remove("simulation");
    config["sets"]["training"] = std::vector<std::string>{"zz10s_a", "zz20s_a", "zz35p_a", "zz20s_b"};
    config["sets"]["held_out"] = std::vector<std::string>{"zz10p_a", "zz35s_a"};
    if (threads >= 0) config["stages"][1]["local"]["num_threads"] = threads;
    if (global_threads >= 0) {
      YAML::Node global;
      global["points"] = 12;
      global["short_iterations"] = 3;
      global["threads"] = global_threads;
      config["stages"][1]["global"] = global;
    }
    const fs::path file = *dir_ / (name + ".yaml");
    std::ofstream(file) << YAML::Dump(config) << "\n";
    const std::string run = std::string(VESSELID_BINARY) + " run " + file.string() + " --data " +
                            dir_->string() + " --out " + (*dir_ / name).string() + " --quiet " +
                            flags + " > /dev/null 2>&1";
    return std::system(run.c_str());
  }
  static json Results(const std::string& name) {
    std::ifstream in(*dir_ / name / "results.json");
    json results = json::parse(in, nullptr, false);
    DropTimes(&results);
    if (results.is_object()) results.erase("config");
    return results;
  }

  static fs::path* dir_;
  static bool simulated_;
};

fs::path* ThreadCount::dir_ = nullptr;
bool ThreadCount::simulated_ = false;

TEST_F(ThreadCount, EstimatesCostsAndErrorsAreTheSameOnAnyNumberOfThreads) {
  ASSERT_TRUE(simulated_);
  ASSERT_EQ(Run("one", 1), 0);
  const json one = Results("one");
  ASSERT_FALSE(one.is_discarded());
  const json& stage = one["stages"][1];
  ASSERT_EQ(stage["name"], "output_error");
  ASSERT_GT(stage["iterations"].get<int>(), 0);
  ASSERT_FALSE(stage["validation"].empty()) << "the held-out runs are part of the comparison";
  ASSERT_FALSE(stage["velocity_validation"].empty()) << "measured per record in parallel";
  for (int threads : {2, 3, 0}) {
    const std::string name = "threads" + std::to_string(threads);
    ASSERT_EQ(Run(name, threads), 0) << threads << " threads";
    const json other = Results(name);
    EXPECT_TRUE(other == one) << threads << " threads: results.json differs beyond its timings:\n"
                              << Differences(one, other);
  }
  // Absent means the machine's cores: the same as 0.
  ASSERT_EQ(Run("default", -1), 0);
  const json absent = Results("default");
  EXPECT_TRUE(absent == one) << Differences(one, absent);
}

// The multistart's short solves run on its own threads, each on a clone of the problem with
// its own evaluation caches; which clone solves which point must not matter.
TEST_F(ThreadCount, MultistartIsTheSameOnAnyNumberOfThreads) {
  ASSERT_TRUE(simulated_);
  ASSERT_EQ(Run("global1", 1, "", 1), 0);
  const json one = Results("global1");
  ASSERT_FALSE(one.is_discarded());
  ASSERT_TRUE(one["stages"][1].contains("global_start")) << one["stages"][1].dump().substr(0, 400);
  for (int threads : {2, 3}) {
    const std::string name = "global" + std::to_string(threads);
    ASSERT_EQ(Run(name, 1, "", threads), 0) << threads << " threads";
    const json other = Results(name);
    EXPECT_TRUE(other == one) << threads << " threads: results.json differs beyond its timings:\n"
                              << Differences(one, other);
  }
}

TEST_F(ThreadCount, NoReportWritesResultsAndTextButNoHtml) {
  ASSERT_TRUE(simulated_);
  const fs::path out = *dir_ / "batch";
  // An earlier run's report in the folder must not pass for this run's.
  ASSERT_EQ(Run("batch", -1), 0);
  ASSERT_TRUE(fs::exists(out / "report.html"));
  ASSERT_EQ(Run("batch", -1, "--no-report"), 0);
  EXPECT_TRUE(fs::exists(out / "results.json"));
  EXPECT_TRUE(fs::exists(out / "report.txt"));
  EXPECT_TRUE(fs::exists(out / "traces" / "output_error.zz10s_a.csv"));
  EXPECT_FALSE(fs::exists(out / "report.html"));
  // The same numbers as a run with its report.
  ASSERT_EQ(Run("with_report", -1), 0);
  EXPECT_TRUE(fs::exists(*dir_ / "with_report" / "report.html"));
  const json batch = Results("batch"), with_report = Results("with_report");
  EXPECT_TRUE(batch == with_report) << Differences(with_report, batch);
}

}  // namespace thread_count_test
}  // namespace vesselid

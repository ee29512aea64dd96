// Where a whole `vesselid run` spends its time: the solves against everything around them
// (loading and fingerprinting the data, validation, held-out runs, checkpoints, traces,
// report.txt, report.html, results.json), per shipped config and on a tank-like case of four
// zigzags (tank_zigzags.yaml, first-order Nomoto on the tanker campaign's data).
//
//   build/tests/benchmarks/benchmark_overheads [--one-thread] [--binary <vesselid>] [config ...]
//
// Each config's data are simulated first (`vesselid simulate`), then it is run as a user
// would, once with report.html and once with --no-report. Per run: wall and CPU time of the
// process, and the wall-time shares of
//   solve   the local refinements and global search of every output-error stage, and the
//           whole of the least-squares and step-regression stages (results.json times);
//   stage   the rest of the stages: continuation, experiments built, uncertainty, fits and
//           their residual analysis;
//   outside the process's wall time outside the stages: config, reading and checking data,
//           validation and held-out runs, checkpoints, traces and reports.
// The target is outside <= 20 % with report.html. --one-thread sets local.num_threads: 1 in
// every stage (the default before threads were the machine's cores); --binary times another
// build of vesselid (one without --no-report prints n/a there).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "nlohmann/json.hpp"
#include "yaml-cpp/yaml.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Timing {
  bool ok = false;
  double wall = 0.0;
  double cpu = 0.0;  // user + system of the process and its threads
};

double Cpu(const rusage& usage) {
  return usage.ru_utime.tv_sec + usage.ru_utime.tv_usec * 1e-6 + usage.ru_stime.tv_sec +
         usage.ru_stime.tv_usec * 1e-6;
}

Timing Timed(const std::string& command) {
  rusage before{}, after{};
  getrusage(RUSAGE_CHILDREN, &before);
  const auto start = std::chrono::steady_clock::now();
  Timing t;
  t.ok = std::system(command.c_str()) == 0;
  t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  getrusage(RUSAGE_CHILDREN, &after);
  t.cpu = Cpu(after) - Cpu(before);
  if (!t.ok) std::fprintf(stderr, "failed: %s\n", command.c_str());
  return t;
}

// Seconds of the solves and of the stages as a whole, from results.json.
void StageTimes(const json& results, double* solve, double* stages) {
  *solve = *stages = 0.0;
  for (const json& stage : results["stages"]) {
    const double total = stage.value("time_seconds", 0.0);
    *stages += total;
    double own = 0.0;
    if (stage.contains("refinements") && !stage["refinements"].empty()) {
      for (const json& r : stage["refinements"]) own += r.value("time_seconds", 0.0);
      if (stage.contains("global_start")) own += stage["global_start"].value("time_seconds", 0.0);
    } else {
      own = total;  // least squares, step regression: the estimation is the stage
    }
    *solve += std::min(own, total);
  }
}

struct Case {
  std::string name;        // as printed
  std::string config;      // the config run
  std::string simulation;  // the config whose simulation makes the data
};

}  // namespace

int main(int argc, char** argv) {
  const std::string source = VESSELID_SOURCE_DIR;
  bool one_thread = false;
  std::string binary = VESSELID_BINARY;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--one-thread")
      one_thread = true;
    else if (arg == "--binary" && i + 1 < argc)
      binary = argv[++i];
    else
      names.push_back(arg);
  }
  std::vector<Case> cases;
  if (names.empty()) {
    for (const auto& entry : fs::directory_iterator(source + "/configs")) {
      if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    names.push_back("tank_zigzags");
  }
  for (const std::string& name : names) {
    if (name == "tank_zigzags") {
      cases.push_back({name, source + "/tests/benchmarks/tank_zigzags.yaml",
                       source + "/configs/nomoto_tanker.yaml"});
    } else {
      const std::string config = source + "/configs/" + name + ".yaml";
      cases.push_back({name, config, config});
    }
  }
  const fs::path dir = fs::temp_directory_path() / "vesselid_benchmark_overheads";
  std::printf("%s; shares of the wall time (solve | rest of the stages | outside the stages)\n",
              one_thread ? "local.num_threads: 1" : "threads: the config's (default: all cores)");
  std::printf("%-20s %8s %8s %6s %6s %8s   %8s %8s %8s\n", "config", "wall s", "cpu s", "solve",
              "stage", "outside", "no-report", "cpu s", "outside");
  for (const Case& c : cases) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    if (!Timed(binary + " simulate " + c.simulation + " --out " + (dir / "data").string() +
               " > /dev/null")
             .ok) {
      return 1;
    }
    YAML::Node config = YAML::LoadFile(c.config);
    config.remove("study");
    if (one_thread) {
      for (YAML::Node stage : config["stages"]) stage["local"]["num_threads"] = 1;
    }
    const fs::path file = dir / (c.name + ".yaml");
    std::ofstream(file) << YAML::Dump(config) << "\n";
    auto run = [&](const std::string& out, const std::string& flags, json* results) {
      const Timing t = Timed(binary + " run " + file.string() + " --data " +
                             (dir / "data").string() + " --out " + (dir / out).string() +
                             " --quiet " + flags + " > /dev/null 2>&1");
      std::ifstream in(dir / out / "results.json");
      *results = json::parse(in, nullptr, false);
      return t;
    };
    json with_report, without;
    const Timing full = run("full", "", &with_report);
    if (!full.ok || with_report.is_discarded()) return 1;
    const Timing batch = run("batch", "--no-report", &without);
    double solve = 0.0, stages = 0.0, batch_solve = 0.0, batch_stages = 0.0;
    StageTimes(with_report, &solve, &stages);
    std::printf("%-20s %8.2f %8.2f %5.0f%% %5.0f%% %7.0f%%", c.name.c_str(), full.wall, full.cpu,
                100.0 * solve / full.wall, 100.0 * (stages - solve) / full.wall,
                100.0 * (full.wall - stages) / full.wall);
    if (batch.ok && !without.is_discarded()) {
      StageTimes(without, &batch_solve, &batch_stages);
      std::printf("   %8.2f %8.2f %7.0f%%\n", batch.wall, batch.cpu,
                  100.0 * (batch.wall - batch_stages) / batch.wall);
    } else {
      std::printf("   %8s\n", "n/a");
    }
    std::fflush(stdout);
  }
  fs::remove_all(dir);
  return 0;
}

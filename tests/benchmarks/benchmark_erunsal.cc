// Benchmark: seed 002's hierarchy (configs/erunsal_hierarchy.yaml) on the simulated reference
// campaign, from starts 30 % off. Reports the campaign simulation time, each stage's wall
// time (continuation, global start, refinements, covariance, validation) and the whole run,
// the problem sizes, and the peak resident memory.
// Run: build/tests/benchmarks/benchmark_erunsal [config.yaml]
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "engine/config/config.h"
#include "engine/diagnose/run_findings.h"
#include "engine/run/pipeline.h"
#include "engine/run/records.h"
#include "problems/registry.h"
#include "tests/benchmarks/benchmark_campaign.h"

namespace vesselid {
namespace {

using benchmark::Clock;
using benchmark::Seconds;

int Main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1]
                                    : std::string(VESSELID_SOURCE_DIR) +
                                          "/configs/erunsal_hierarchy.yaml";
  const ModelRegistry registry = DefaultRegistry();
  RunConfig config;
  std::string error;
  double simulation_seconds;
  if (!benchmark::LoadAndSimulate(path, "vesselid_benchmark_erunsal", registry, &config,
                                  &simulation_seconds, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("campaign simulation: %.3f s (%zu experiments)\n", simulation_seconds,
              config.experiments.size());
  auto start = Clock::now();

  Clock::time_point stage_start;
  RunResult result;
  start = Clock::now();
  RunObserver observer;
  observer.stage_started = [&](size_t, const std::string&) { stage_start = Clock::now(); };
  observer.stage_finished = [&](size_t, const StageResult& finished, std::string*) {
    const StageSummary& s = finished.summary;
    std::set<std::string> experiments;
    for (const Estimate& e : finished.estimates) {
      if (!e.experiment.empty()) experiments.insert(e.experiment);
    }
    std::printf(
        "stage %-8s %8.3f s wall  %3d iterations  cost %.4e  "
        "%3zu experiments/segments  %4zu variables\n",
        s.name.c_str(), Seconds(stage_start), s.local().iterations, s.local().final_cost,
        experiments.size(), finished.estimates.size());
    return true;
  };
  const bool ok = Identify(config, &result, &error, observer);
  const double total = Seconds(start);
  std::filesystem::remove_all(benchmark::DataFolder("vesselid_benchmark_erunsal"));
  if (!ok) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("whole hierarchy: %.3f s (including final validation)\n", total);
  double worst_r2 = 1.0;
  for (const ExperimentFit& fit : result.final_validation) {
    for (const ChannelMetrics& c : fit.channels) worst_r2 = std::min(worst_r2, c.r2);
  }
  std::printf("final validation: worst R^2 %.6f\n", worst_r2);
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  std::printf("peak resident memory: %.1f MB\n", usage.ru_maxrss / 1024.0);
  return 0;
}

}  // namespace
}  // namespace vesselid

int main(int argc, char** argv) { return vesselid::Main(argc, argv); }

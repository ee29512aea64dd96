// Benchmark: seed 004's pipeline on the shipped campaign, stage by stage. Simulates the step
// campaign and validation runs, then runs configs/eriksen_2dof.yaml and reports the time of
// each pipeline step: campaign simulation, regression data (records), steady-state windows,
// first-order step fits, normalisation, lasso path with leave-one-group-out CV per term
// (with the (a, b) grid of the inertia terms), the output-error refinement, and the free-run
// validation, with the validation NRMSE fit % of U and r after each stage.
// Run: build/tests/benchmarks/benchmark_eriksen [config.yaml]
#include <sys/resource.h>

#include <cstdio>

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

// Sample-weighted mean fit % of one output over a stage's validation runs.
double MeanFit(const std::vector<ExperimentFit>& fits, const std::string& output) {
  double sum = 0.0;
  int samples = 0;
  for (const ExperimentFit& fit : fits) {
    for (const ChannelMetrics& m : fit.channels) {
      if (m.output != output) continue;
      sum += m.fit_percent * m.samples;
      samples += m.samples;
    }
  }
  return samples > 0 ? sum / samples : 0.0;
}

int Main(int argc, char** argv) {
  const std::string path =
      argc > 1 ? argv[1] : std::string(VESSELID_SOURCE_DIR) + "/configs/eriksen_2dof.yaml";
  const ModelRegistry registry = DefaultRegistry();
  RunConfig config;
  std::string error;
  double simulation_seconds;
  if (!benchmark::LoadAndSimulate(path, "vesselid_benchmark_eriksen", registry, &config,
                                  &simulation_seconds, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("campaign simulation (steps + validation): %8.3f s\n", simulation_seconds);

  // The regression data alone (the stage reads them again through its cache).
  const StageConfig& regression = config.stages.at(0);
  TrajectoryCache cache;
  std::vector<RegressionRecord> records;
  auto start = Clock::now();
  if (!PrepareRegressionRecords(config, regression.experiments, *config.model,
                                regression.regression_data, &cache, &records, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  int rows = 0;
  for (const RegressionRecord& r : records) rows += r.size();
  std::printf("regression records (%zu runs, %d rows):  %8.3f s\n", records.size(), rows,
              Seconds(start));

  RunResult result;
  start = Clock::now();
  if (!Identify(config, &result, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const double total = Seconds(start);
  for (const StageResult& stage : result.stages) {
    if (stage.step_regression) {
      const StepRegressionReport& r = *stage.step_regression;
      std::printf("stage %s (%.3f s in all):\n", stage.name.c_str(), stage.summary.time_seconds);
      std::printf("  steady-state windows (%d intervals):  %8.3f s\n", r.samples.intervals,
                  r.samples.window_seconds);
      std::printf("  first-order step fits (%d steps):     %8.3f s\n", r.samples.steps,
                  r.samples.fit_seconds);
      std::printf("  normalisation:                        %8.3f s\n", r.normalisation_seconds);
      for (const TermRegression& t : r.terms) {
        std::printf("  lasso + LOO-CV %-8s (%3d samples, %3zu (a,b) points, %zu lambdas): %7.3f s\n",
                    t.name.c_str(), t.samples, std::max<size_t>(t.asymptote_grid.size(), 1),
                    t.path.lambda.size(), t.seconds);
      }
    } else {
      const LocalSolveSummary& l = stage.summary.local();
      std::printf("stage %s: %d iterations, %.3f s (Ceres %.3f s), cost %.6g -> %.6g\n",
                  stage.name.c_str(), l.iterations, stage.summary.time_seconds, l.time_seconds,
                  l.initial_cost, l.final_cost);
    }
    std::printf("  validation fit %%: U %.2f, r %.2f\n", MeanFit(stage.validation, "U"),
                MeanFit(stage.validation, "r"));
  }
  std::printf("whole run: %.3f s\n", total);
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  std::printf("peak memory: %.1f MB\n", usage.ru_maxrss / 1024.0);
  return 0;
}

}  // namespace
}  // namespace vesselid

int main(int argc, char** argv) { return vesselid::Main(argc, argv); }

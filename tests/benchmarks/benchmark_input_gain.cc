// Benchmark: seed 000's input-gain campaign (127 segments, 53.4 min). Simulates the campaign,
// runs the least-squares stage, then times the output-error refinement over every training
// segment (23 parameters + 6 initial states per segment) from that start with three Ceres
// linear solvers for the same number of iterations:
//   sparse_normal_cholesky (SuiteSparse; J^T J is an arrow matrix: a dense corner of shared
//   parameters and a block diagonal of per-segment states), dense_normal_cholesky, dense_qr.
// Also reports the run's velocity metrics (least squares vs refinement) and peak memory.
// Run: build/tests/benchmarks/benchmark_input_gain [config.yaml] [iterations]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "engine/config/config.h"
#include "engine/run/least_squares_stage.h"
#include "engine/diagnose/run_findings.h"
#include "engine/run/pipeline.h"
#include "engine/run/records.h"
#include "engine/solve/local_solve.h"
#include "engine/study/partition_study.h"
#include "problems/registry.h"
#include "tests/benchmarks/benchmark_campaign.h"

namespace vesselid {
namespace {

using benchmark::Clock;
using benchmark::Seconds;

int Main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1]
                                    : std::string(VESSELID_SOURCE_DIR) +
                                          "/configs/input_gain_static.yaml";
  const int iterations = argc > 2 ? std::atoi(argv[2]) : 10;
  const ModelRegistry registry = DefaultRegistry();
  RunConfig config;
  std::string error;
  double simulation_seconds;
  if (!benchmark::LoadAndSimulate(path, "vesselid_benchmark_input_gain", registry, &config,
                                  &simulation_seconds, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("campaign simulation: %.3f s\n", simulation_seconds);
  auto start = Clock::now();

  // The least-squares start.
  const StageConfig& ls_stage = config.stages.at(0);
  const StageConfig& oe_stage = config.stages.at(1);
  const ModelHandle& model = *config.model;
  const ModelInfo& info = model.info();
  std::vector<ParameterSpec> specs = StudyParameterSpecs(ls_stage, info);
  TrajectoryCache cache;
  StageResult ls;
  start = Clock::now();
  if (!RunLeastSquaresStage(config, ls_stage, model, specs, &cache, &ls, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("least-squares stage: %.3f s\n", Seconds(start));
  std::vector<ParameterSpec> refined;
  for (size_t i = 0; i < info.parameters.size(); ++i) {
    ParameterSpec s;
    s.name = info.parameters[i];
    s.start = ls.estimates[i].value;
    bool listed = false;
    for (const ParameterSpec& o : oe_stage.parameters) listed |= o.name == s.name;
    if (!listed) s.role = ParameterRole::kFixed;
    refined.push_back(s);
  }
  std::vector<Experiment> experiments;
  if (!PrepareExperiments(config, oe_stage.experiments, model, oe_stage.experiment, &cache,
                          &experiments, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  int samples = 0;
  for (const Experiment& e : experiments) samples += e.num_samples();
  std::printf("refinement: %zu segments, %d residuals\n", experiments.size(), samples);

  double sparse_time = 0.0;
  for (ceres::LinearSolverType solver :
       {ceres::SPARSE_NORMAL_CHOLESKY, ceres::DENSE_NORMAL_CHOLESKY, ceres::DENSE_QR}) {
    auto problem =
        OutputErrorProblem::Create(&model, experiments, refined, oe_stage.problem, &error);
    if (problem == nullptr) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
    LocalSolveOptions options;
    options.linear_solver = solver;
    options.max_iterations = iterations;
    options.function_tolerance = options.gradient_tolerance = options.parameter_tolerance = 0.0;
    LocalSolveSummary summary;
    start = Clock::now();
    RunLocalSolve(options, problem.get(), &summary);
    const double seconds = Seconds(start);
    if (solver == ceres::SPARSE_NORMAL_CHOLESKY) sparse_time = seconds;
    std::printf("  %-24s %3d iterations %8.3f s (%.3f s/iteration), cost %.6e -> %.6e, "
                "%d unknowns, x%.1f of sparse\n",
                ceres::LinearSolverTypeToString(solver), summary.iterations, seconds,
                seconds / std::max(1, summary.iterations), summary.initial_cost,
                summary.final_cost, problem->num_free(), seconds / sparse_time);
  }

  // The whole run (least squares, refinement, validations) and its velocity metrics.
  RunResult result;
  start = Clock::now();
  if (!Identify(config, &result, &error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  std::printf("whole run: %.3f s\n", Seconds(start));
  for (const StageResult& stage : result.stages) {
    std::printf("stage %s (%.3f s): velocity validation\n", stage.name.c_str(),
                stage.summary.time_seconds);
    for (const ChannelMetrics& m : stage.velocity_validation) {
      std::printf("  %-30s %s  MAE %.4f  RMSE %.4f  R2 %.5f\n", m.experiment.c_str(),
                  m.output.c_str(), m.mae, m.rmse, m.r2);
    }
  }
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  std::printf("peak resident memory: %.1f MB\n", usage.ru_maxrss / 1024.0);
  return 0;
}

}  // namespace
}  // namespace vesselid

int main(int argc, char** argv) { return vesselid::Main(argc, argv); }

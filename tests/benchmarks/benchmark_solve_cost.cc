// Benchmark: what a solve costs beyond its evaluations, and what a campaign holds in memory.
//   1. Seed 003 cargo, noise-free, from the shipped start (T1, T3 x1.5, T2, K /1.5): the stage
//      (local solve, covariance, HAC, local analysis, fit metrics) on the single sine with and
//      without a free initial heading, and on a multi-sine. Prints the time per iteration, the
//      share of the local solve spent in residual and Jacobian evaluations (Ceres' own
//      accounting), the stage's time outside the local solve, the ratio of the time per
//      iteration with the free heading to that without it, and the time per iteration in
//      simulations of the record in double (the engine's own simulator), the physical limit of
//      a forward-mode Gauss-Newton iteration being about 2 (one residual evaluation, one Jet
//      simulation). Both with Levenberg-Marquardt and with the reflective region (which
//      evaluates residuals and Jacobian once per trial point and steps on the normal equations).
//   2. Peak RSS of `vesselid run` on an input-gain campaign enlarged to ~200 000 training rows
//      over ~110 segments (configs/input_gain_static.yaml, 157 segments over 80 minutes, the
//      refinement limited to `iterations` iterations), measured on the child process.
// Run: build/tests/benchmarks/benchmark_solve_cost [iterations]   (0 iterations: part 1 only)
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"
#include "problems/nomoto/handles.h"
#include "tests/benchmarks/benchmark_campaign.h"
#include "tests/support/nomoto_data.h"

extern char** environ;

namespace vesselid {
namespace {

using benchmark::Clock;
using benchmark::MeanTime;
using benchmark::Seconds;

struct CargoTimes {
  double stage = 0, local = 0, per_iteration = 0, evaluation_share = 0, outside = 0;
  double simulation = 0;  // one simulation of the record in double (the physical limit's unit)
  int iterations = 0;
  int residual_evaluations = 0, jacobian_evaluations = 0;  // Ceres' counts (cache hits too)
  // What the local solve simulated (double, Jet) and copied from the evaluation cache.
  long simulations = 0, jet_simulations = 0, copies = 0;
  long stage_simulations = 0, stage_jet_simulations = 0, stage_copies = 0;  // the whole stage
};

// The cargo record: the shipped single sine, or the multi-sine of nomoto_cargo_noise.yaml
// (noise-free), from which a start 1.5x off needs about as many iterations of any
// Gauss-Newton solver, so that the time per iteration decides.
testing::SeedVessel Cargo(bool multisine) {
  testing::SeedVessel vessel = testing::CargoVessel();
  if (multisine) {
    vessel.loop.excitation.type = nomoto::Excitation::Type::kMultisine;
    vessel.loop.excitation.periods = {600, 300, 150, 75, 40, 20};
  }
  return vessel;
}

CargoTimes TimeCargo(const std::vector<std::string>& free_states, bool multisine,
                     TrustRegion method) {
  auto model = nomoto::MakeSecondOrderHandle();
  const testing::SeedVessel vessel = Cargo(multisine);
  Experiment e = testing::MakeExperiment(*model, vessel.truth, vessel.loop);
  std::vector<double> outputs;
  const std::vector<double> x0 = e.initial_state;
  const double simulation = MeanTime(
      [&] { model->SimulateOutputs(e, vessel.truth.data(), x0.data(), &outputs); }, 0.5);
  OutputErrorOptions options;
  options.free_initial_states = free_states;
  std::string error;
  auto problem = OutputErrorProblem::Create(model.get(), {e}, testing::FiftyPercentOff(vessel.truth),
                                            options, &error);
  StageOptions stage;
  stage.local.trust_region = method;
  StageSummary summary;
  // The stage's local solve only (RunStage's solve runs first; its analysis evaluates after).
  long counted[3] = {0, 0, 0};
  stage.local.progress = [&](const SolveProgress&) {
    const EvaluationCounts& c = problem->evaluation_counts();
    counted[0] = c.simulations;
    counted[1] = c.jet_simulations;
    counted[2] = c.hits;
  };
  const auto start = Clock::now();
  if (!RunStage(stage, problem.get(), &summary)) {
    std::fprintf(stderr, "cargo stage failed: %s\n", summary.message.c_str());
    std::exit(1);
  }
  CargoTimes t;
  t.stage = Seconds(start);
  const LocalSolveSummary& local = summary.local();
  t.local = local.time_seconds;
  t.iterations = local.iterations;
  t.per_iteration = local.time_seconds / std::max(1, local.iterations);
  t.evaluation_share = (local.residual_seconds + local.jacobian_seconds) / local.time_seconds;
  t.outside = t.stage - t.local;
  t.simulation = simulation;
  t.residual_evaluations = local.residual_evaluations;
  t.jacobian_evaluations = local.jacobian_evaluations;
  t.simulations = counted[0];
  t.jet_simulations = counted[1];
  t.copies = counted[2];
  const EvaluationCounts& all = problem->evaluation_counts();
  t.stage_simulations = all.simulations;
  t.stage_jet_simulations = all.jet_simulations;
  t.stage_copies = all.hits;
  return t;
}

// Time of one cargo residual + Jacobian evaluation for 1..8 free blocks (T1 T2 T3 K delta_0,
// then the three initial states), relative to a residual-only evaluation.
void TimeJetWidths() {
  auto model = nomoto::MakeSecondOrderHandle();
  const testing::SeedVessel vessel = testing::CargoVessel();
  Experiment e = testing::MakeExperiment(*model, vessel.truth, vessel.loop);
  std::vector<double> scales = {45.0, 6.0, 10.0, 0.09, 1.0};
  std::vector<double> theta = {1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0};
  std::vector<const double*> blocks;
  for (double& t : theta) blocks.push_back(&t);
  std::vector<double> residuals(e.num_samples());
  std::vector<std::vector<double>> jacobian(8, std::vector<double>(e.num_samples()));
  std::unique_ptr<ceres::CostFunction> cost(model->NewExperimentCost(&e, scales, nullptr));
  const double plain =
      MeanTime([&] { cost->Evaluate(blocks.data(), residuals.data(), nullptr); }, 0.3);
  std::printf("cargo evaluation, %d samples: residuals only %.1f ms; with Jacobian, by free "
              "blocks:\n ", e.num_samples(), 1e3 * plain);
  for (int d = 1; d <= 8; ++d) {
    std::vector<double*> jacobian_blocks(8, nullptr);
    for (int i = 0; i < d; ++i) jacobian_blocks[i] = jacobian[i].data();
    const double t = MeanTime(
        [&] { cost->Evaluate(blocks.data(), residuals.data(), jacobian_blocks.data()); }, 0.3);
    std::printf(" %d: %.1f ms (%.2fx)", d, 1e3 * t, t / plain);
  }
  std::printf("\n");
}

// Runs `argv` and returns its peak RSS in MB (-1 on failure).
double PeakRssMb(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  struct rusage usage {};
  if (wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    return -1;
  }
  return usage.ru_maxrss / 1024.0;
}

int Main(int argc, char** argv) {
  const int iterations = argc > 1 ? std::atoi(argv[1]) : 2;
  TimeJetWidths();
  for (TrustRegion method : {TrustRegion::kLevenbergMarquardt, TrustRegion::kReflective}) {
    const char* solver = TrustRegionToString(method);
    std::printf("cargo, noise-free, 1.5x off, %s\n", solver);
    std::printf(
        "                              stage s  local s  iters  s/iter  eval share  "
        "outside solve s  sim s  iter/sim  stage/local\n");
    const CargoTimes plain = TimeCargo({}, false, method);
    const CargoTimes heading = TimeCargo({"psi"}, false, method);
    const CargoTimes multisine = TimeCargo({}, true, method);
    for (const auto& [name, t] : {std::pair{"sine, parameters only", plain},
                                  {"sine, free initial psi", heading},
                                  {"multi-sine, parameters only", multisine}}) {
      std::printf("  %-27s %8.3f %8.3f %6d %7.4f %10.1f%% %16.3f %6.3f %9.2f %12.2f\n", name,
                  t.stage, t.local, t.iterations, t.per_iteration, 100 * t.evaluation_share,
                  t.outside, t.simulation, t.per_iteration / t.simulation, t.stage / t.local);
    }
    std::printf(
        "  multi-sine: %d iterations, %d residual and %d Jacobian evaluations asked by "
        "Ceres\n",
        multisine.iterations, multisine.residual_evaluations, multisine.jacobian_evaluations);
    std::printf(
        "  multi-sine: %ld double and %ld Jet simulations, %ld copies from the evaluation "
        "cache (to the solve's last iteration)\n",
        multisine.simulations, multisine.jet_simulations, multisine.copies);
    std::printf("  multi-sine: the whole stage %ld double and %ld Jet simulations, %ld copies\n",
                multisine.stage_simulations, multisine.stage_jet_simulations,
                multisine.stage_copies);
    std::printf(
        "  multi-sine: time per iteration %.2f double simulations (target <= 2.5), "
        "stage / local solve %.2f (target <= 1.2)\n",
        multisine.per_iteration / multisine.simulation, multisine.stage / multisine.local);
    std::printf("  time per iteration, free psi / without: %.2f (target <= 1.3)\n",
                heading.per_iteration / plain.per_iteration);
    std::printf("  stage time outside the local solve / local solve: %.2f\n",
                plain.outside / plain.local);
  }
  if (iterations <= 0) return 0;

  // The enlarged input-gain campaign, through the command line.
  const std::filesystem::path folder = benchmark::DataFolder("vesselid_benchmark_solve_cost");
  std::filesystem::create_directories(folder);
  std::ifstream in(std::string(VESSELID_SOURCE_DIR) + "/configs/input_gain_static.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string config = text.str();
  auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = config.find(from);
    if (at == std::string::npos) {
      std::fprintf(stderr, "configs/input_gain_static.yaml has no '%s'\n", from.c_str());
      std::exit(1);
    }
    config.replace(at, from.size(), to);
  };
  replace("segments: 127", "segments: 157");
  replace("duration_min: 53.42", "duration_min: 80");
  replace("  - name: refinement\n",
          "  - name: refinement\n    local: {max_iterations: " + std::to_string(iterations) + "}\n");
  const std::string path = (folder / "big.yaml").string();
  std::ofstream(path) << config;
  const std::string data = (folder / "data").string(), out = (folder / "out").string();
  if (PeakRssMb({VESSELID_BINARY, "simulate", path, "--out", data}) < 0) {
    std::fprintf(stderr, "simulating %s failed\n", path.c_str());
    return 1;
  }
  const auto start = Clock::now();
  const double rss = PeakRssMb({VESSELID_BINARY, "run", path, "--data", data, "--out", out});
  if (rss < 0) {
    std::fprintf(stderr, "vesselid run %s failed\n", path.c_str());
    return 1;
  }
  std::printf("input gain, 157 segments / 80 min (refinement %d iterations): run %.1f s, "
              "peak RSS %.0f MB, / 400 MB target: %.2f\n",
              iterations, Seconds(start), rss, rss / 400.0);
  return 0;
}

}  // namespace
}  // namespace vesselid

int main(int argc, char** argv) { return vesselid::Main(argc, argv); }

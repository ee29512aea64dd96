// Benchmark: the cost of each uncertainty method relative to the stage's solve, on seed 003's
// cargo (6000 s) and patrol (900 s) multi-sine records at 50 Hz with 0.1 deg noise on the
// logged rudder and heading, solved locally from 10 % off the truth. Hessian: Ceres'
// covariance (covariance.h); HAC: one more Jacobian evaluation and the long-run covariance
// (hac_covariance.h); auto = both; block_bootstrap: re-solves of the stage from its estimate
// (bootstrap_uncertainty.h), timed over a few replicates on one thread and reported for the
// default 100; experiment_bootstrap: the same on six patrol records of 150 s (a segmented
// case). Run: build/tests/benchmarks/benchmark_uncertainty
#include <chrono>
#include <cstdio>

#include "engine/run/bootstrap_uncertainty.h"
#include "engine/solve/hac_covariance.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"
#include "problems/nomoto/handles.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kTimedReplicates = 4;  // replicates timed, on one thread
constexpr int kDefaultRuns = BootstrapOptions().runs;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// Seconds per replicate of `method` at the solved problem (kTimedReplicates on one thread).
double ReplicateSeconds(UncertaintyMethod method, const StageOptions& solved_with,
                        const OutputErrorOptions& problem_options, OutputErrorProblem* problem,
                        const StageSummary& summary, int* failed) {
  StageOptions options = solved_with;
  options.compute_uncertainty = true;
  options.uncertainty.method = method;
  options.uncertainty.bootstrap.runs = kTimedReplicates;
  options.uncertainty.bootstrap.num_threads = 1;
  StageSummary copy = summary;
  const auto start = Clock::now();
  BootstrapStageUncertainty(options, problem_options, problem, &copy);
  *failed = copy.uncertainty.bootstrap_failed;
  return Seconds(start) / kTimedReplicates;
}

void Report(const char* name, testing::SeedVessel vessel, int records = 1) {
  auto model = nomoto::MakeSecondOrderHandle();
  vessel.loop.excitation.type = nomoto::Excitation::Type::kMultisine;
  vessel.loop.excitation.periods = {60, 30, 15, 7.5, 4, 2};
  if (vessel.truth[0] > 10) vessel.loop.excitation.periods = {600, 300, 150, 75, 40, 20};
  vessel.loop.rudder_noise = vessel.loop.heading_noise = 0.1 * M_PI / 180.0;
  std::vector<Experiment> experiments;
  for (int i = 0; i < records; ++i) {
    vessel.loop.seed = 12 + i;
    experiments.push_back(testing::MakeExperiment(*model, vessel.truth, vessel.loop,
                                                  Interpolation::kCubic,
                                                  "run" + std::to_string(i)));
  }
  const Experiment& e = experiments[0];
  OutputErrorOptions problem_options;
  problem_options.free_initial_states = {"psi"};
  std::string error;
  // Started 10 % off the truth: from 50 % off without the configs' global start the patrol
  // refinement ends on the T1 = T2 ridge, a misfit whose residuals the HAC rightly inflates.
  std::vector<ParameterSpec> specs = testing::FiftyPercentOff(vessel.truth);
  for (int i = 0; i < 4; ++i) specs[i].start = 1.1 * vessel.truth[i];
  auto problem =
      OutputErrorProblem::Create(model.get(), experiments, specs, problem_options, &error);
  if (problem == nullptr) {
    std::printf("%s: %s\n", name, error.c_str());
    return;
  }
  StageOptions options;
  options.compute_uncertainty = false;
  StageSummary summary;
  auto start = Clock::now();
  if (!RunStage(options, problem.get(), &summary)) {
    std::printf("%s: %s\n", name, summary.message.c_str());
    return;
  }
  const double solve = Seconds(start);
  start = Clock::now();
  Uncertainty hessian, hac;
  ComputeUncertainty(problem.get(), summary.local().final_cost, &hessian);
  const double hessian_seconds = Seconds(start);
  start = Clock::now();
  ComputeHacCovariance(HacOptions(), problem.get(), hessian, &hac);
  const double hac_seconds = Seconds(start);
  summary.uncertainty = hessian;
  int failed = 0;
  const UncertaintyMethod bootstrap = records >= kMinBootstrapExperiments
                                          ? UncertaintyMethod::kExperimentBootstrap
                                          : UncertaintyMethod::kBlockBootstrap;
  const double replicate =
      ReplicateSeconds(bootstrap, options, problem_options, problem.get(), summary, &failed);
  std::printf("%-7s %d x %d nodes  %s: %.3f s per replicate (%.3f x solve, %d of %d failed), "
              "%d runs %.1f x solve on one core\n",
              name, records, e.num_nodes(), UncertaintyMethodToString(bootstrap), replicate,
              replicate / solve, failed, kTimedReplicates, kDefaultRuns,
              kDefaultRuns * replicate / solve);
  std::printf(
      "%-7s %6d nodes  solve %.3f s  hessian %.3f s (%.3f x solve)  hac %.3f s (%.3f x)  "
      "auto %.3f x  K %.5g (truth %.5g) SE hessian %.2e hac %.2e\n",
      name, e.num_nodes(), solve, hessian_seconds, hessian_seconds / solve, hac_seconds,
      hac_seconds / solve, (hessian_seconds + hac_seconds) / solve, problem->variables()[3].value(), vessel.truth[3],
      hessian.std_errors[3],
      hac.std_errors[3]);
  std::printf("        T1 %.5g T2 %.5g T3 %.5g (truth %.5g %.5g %.5g), cost %.4e\n",
              problem->variables()[0].value(), problem->variables()[1].value(),
              problem->variables()[2].value(), vessel.truth[0], vessel.truth[1], vessel.truth[2],
              summary.local().final_cost);
}

}  // namespace
}  // namespace vesselid

int main() {
  vesselid::Report("patrol", vesselid::testing::PatrolVessel());
  vesselid::Report("cargo", vesselid::testing::CargoVessel());
  vesselid::testing::SeedVessel segmented = vesselid::testing::PatrolVessel();
  segmented.loop.duration = 150.0;  // six independent records of 150 s
  vesselid::Report("patrol", segmented, 6);
  return 0;
}

// Benchmark: seed 003 cargo and patrol cases, noise-free, from the 50 % off start.
// Reports the total identification time (global start where used, local refinement,
// covariance, metrics), the time of one plain double simulation, of one residual + Jacobian
// evaluation, and their ratio. Run: build/tests/benchmarks/benchmark_nomoto
#include <chrono>
#include <cstdio>

#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"
#include "problems/nomoto/handles.h"
#include "tests/benchmarks/benchmark_campaign.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace {

using benchmark::Clock;
using benchmark::MeanTime;
using benchmark::Seconds;

void Report(const char* name, const testing::SeedVessel& vessel, bool global_start) {
  auto model = nomoto::MakeSecondOrderHandle();
  Experiment e = testing::MakeExperiment(*model, vessel.truth, vessel.loop);
  std::vector<ParameterSpec> specs = testing::FiftyPercentOff(vessel.truth);
  std::string error;
  auto problem = OutputErrorProblem::Create(model.get(), {e}, specs, {}, &error);

  // Blocks of the cost function: T1 T2 T3 K delta_0 (theta = value / scale), x0 (3 states);
  // Jacobians requested for the four free parameters, as in the solve.
  std::vector<double> scales;
  for (const ParameterSpec& s : specs) scales.push_back(s.EffectiveScale());
  scales.push_back(1.0);  // delta_0
  std::vector<double> theta = {1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0};
  std::vector<const double*> blocks;
  for (double& t : theta) blocks.push_back(&t);
  std::vector<double> residuals(e.num_samples()), x0(3, 0.0);
  std::vector<std::vector<double>> jacobian(4, std::vector<double>(e.num_samples()));
  std::vector<double*> jacobian_blocks(8, nullptr);
  for (int i = 0; i < 4; ++i) jacobian_blocks[i] = jacobian[i].data();
  std::unique_ptr<ceres::CostFunction> cost(model->NewExperimentCost(&e, scales, nullptr));
  std::vector<double> p = problem->ParametersOf(0), outputs;
  const double simulate =
      MeanTime([&] { model->SimulateOutputs(e, p.data(), x0.data(), &outputs); }, 0.5);
  const double residual =
      MeanTime([&] { cost->Evaluate(blocks.data(), residuals.data(), nullptr); }, 0.5);
  const double jacobian_time = MeanTime(
      [&] { cost->Evaluate(blocks.data(), residuals.data(), jacobian_blocks.data()); }, 0.5);

  StageOptions options;
  options.use_global_start = global_start;
  options.global.max_evaluations = 400;
  StageSummary summary;
  const auto start = Clock::now();
  RunStage(options, problem.get(), &summary);
  const double total = Seconds(start);
  double worst = 0.0;
  for (int i = 0; i < 4; ++i) {
    worst = std::max(worst, std::abs(problem->variables()[i].value() / vessel.truth[i] - 1.0));
  }
  std::printf("%-7s %8d %9.3f %9.3f %6d %10.2f %10.2f %10.2f %7.2f %10.2e\n", name, e.num_samples(),
              total, summary.local().time_seconds, summary.local().iterations, 1e3 * simulate,
              1e3 * residual, 1e3 * jacobian_time, jacobian_time / simulate, 100 * worst);
}

}  // namespace
}  // namespace vesselid

int main() {
  std::printf("%-7s %8s %9s %9s %6s %10s %10s %10s %7s %10s\n", "case", "samples", "total s",
              "local s", "iters", "sim ms", "resid ms", "jac ms", "jac/sim", "worst err%");
  vesselid::Report("cargo", vesselid::testing::CargoVessel(), false);
  vesselid::Report("patrol", vesselid::testing::PatrolVessel(), true);
  return 0;
}

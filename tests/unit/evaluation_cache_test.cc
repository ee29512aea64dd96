// The experiments' evaluation cache (engine/model/evaluation_cache.h): a solve with it takes
// the same steps to the same estimate (within rounding: residuals copied from a Jet
// simulation may differ from a double one's in the last bits) with one simulation per
// accepted step instead of three, and is reproducible bit for bit.
//
// Data the identified model did not make: a Norrbin ship (cubic yaw damping) behind a
// rate-limited steering gear, with a rudder bias, a slow yaw disturbance, heading noise and a
// quantised compass, identified as a first-order Nomoto model within bounds (the bounds make
// Ceres run its projected line search, which evaluates the gradient at each candidate).
#include "engine/model/evaluation_cache.h"

#include <cmath>
#include <cstdio>

#include "engine/solve/local_solve.h"
#include "engine/solve/output_error_problem.h"
#include "gtest/gtest.h"
#include "tests/support/parameter_spec.h"
#include "problems/nomoto/handles.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace evaluation_cache_test {

nomoto::ClosedLoopOptions Loop(double period, unsigned seed) {
  nomoto::ClosedLoopOptions loop;
  loop.controller_gain = 0.8;
  loop.duration = 150.0;
  loop.sample_time = 0.1;
  loop.excitation.amplitude = 0.35;
  loop.excitation.periods = {period};
  loop.rudder_rate = 0.05;
  loop.rudder_bias = 0.01;
  loop.disturbance_amplitude = 0.02;
  loop.disturbance_period = 90.0;
  loop.heading_noise = 0.004;
  loop.heading_resolution = 0.1 * M_PI / 180.0;
  loop.seed = seed;
  return loop;
}

ParameterSpec Spec(const std::string& name, double start, double lower, double upper) {
  return testing::BoundedSpec(name, start, lower, upper);
}

struct Solved {
  LocalSolveSummary summary;
  std::vector<double> values;
  long simulations = 0, jet_simulations = 0, hits = 0;
};

// One record of a Norrbin ship (T, K, cubic coefficient alpha, no offset) prepared for the
// first-order model, which has no cubic term.
Experiment NorrbinRun(const ModelHandle& model, double period, unsigned seed,
                      const std::string& name) {
  Trajectory trajectory;
  std::string error;
  const auto ship = nomoto::MakeNorrbinHandle();
  EXPECT_TRUE(nomoto::SimulateClosedLoop(*ship, {25.0, 0.12, 4.0, 0.0}, Loop(period, seed),
                                         &trajectory, &error))
      << error;
  trajectory.source = name;
  ExperimentSpec spec;
  spec.name = name;
  spec.inputs = {{"delta", "delta"}};
  spec.outputs = {{"psi", "psi"}};
  Experiment experiment;
  EXPECT_TRUE(
      BuildExperiment(spec, trajectory, model.info(), ExperimentOptions(), &experiment, &error))
      << error;
  return experiment;
}

// Two Norrbin runs fitted with a first-order model from a start 50 % off, on two threads.
Solved Solve(bool cache, bool bounded) {
  const auto model = nomoto::MakeFirstOrderHandle();
  const std::vector<Experiment> runs = {NorrbinRun(*model, 60.0, 7, "run0"),
                                        NorrbinRun(*model, 85.0, 8, "run1")};
  const double inf = INFINITY;
  std::vector<ParameterSpec> specs =
      bounded ? std::vector<ParameterSpec>{Spec("T", 37.5, 1.0, 200.0), Spec("K", 0.08, 0.001, 1.0),
                                           Spec("delta_0", 0.0, -0.1, 0.1)}
              : std::vector<ParameterSpec>{Spec("T", 37.5, -inf, inf), Spec("K", 0.08, -inf, inf),
                                           Spec("delta_0", 0.0, -inf, inf)};
  OutputErrorOptions options;
  options.evaluation_cache = cache;
  std::string error;
  auto problem = OutputErrorProblem::Create(model.get(), runs, specs, options, &error);
  EXPECT_NE(problem, nullptr) << error;
  Solved solved;
  if (problem == nullptr) return solved;
  LocalSolveOptions solve;
  solve.num_threads = 2;
  // The cache serves Ceres' bounded line search, which runs when a linear solver is named
  // (the engine's own regions on the normal equations evaluate each trial point once, with
  // its Jacobian).
  solve.trust_region = TrustRegion::kLevenbergMarquardt;
  solve.linear_solver = ceres::DENSE_NORMAL_CHOLESKY;
  EXPECT_TRUE(RunLocalSolve(solve, problem.get(), &solved.summary)) << solved.summary.message;
  solved.values = problem->Values();
  const EvaluationCounts& counts = problem->evaluation_counts();
  solved.simulations = counts.simulations;
  solved.jet_simulations = counts.jet_simulations;
  solved.hits = counts.hits;
  return solved;
}

void ExpectSameSolve(const Solved& with, const Solved& without) {
  // Bit for bit: every iteration's cost, the steps taken and the estimate.
  EXPECT_EQ(with.summary.cost_history, without.summary.cost_history);
  EXPECT_EQ(with.summary.iterations, without.summary.iterations);
  EXPECT_EQ(with.summary.successful_steps, without.summary.successful_steps);
  EXPECT_EQ(with.summary.unsuccessful_steps, without.summary.unsuccessful_steps);
  EXPECT_EQ(with.summary.final_cost, without.summary.final_cost);
  EXPECT_EQ(with.summary.termination, without.summary.termination);
  EXPECT_EQ(with.values, without.values);
}

TEST(EvaluationCache, BoundedSolveTakesTheSameStepsWithOneJetSimulationPerAcceptedStep) {
  const Solved without = Solve(false, true), with = Solve(true, true);
  ASSERT_TRUE(without.summary.usable && with.summary.usable);
  // The same path: every iteration's cost within rounding, the same steps and estimate.
  ASSERT_EQ(with.summary.cost_history.size(), without.summary.cost_history.size());
  for (size_t i = 0; i < with.summary.cost_history.size(); ++i) {
    EXPECT_NEAR(with.summary.cost_history[i], without.summary.cost_history[i],
                1e-12 * without.summary.cost_history[i]);
  }
  EXPECT_EQ(with.summary.successful_steps, without.summary.successful_steps);
  EXPECT_EQ(with.summary.unsuccessful_steps, without.summary.unsuccessful_steps);
  ASSERT_EQ(with.values.size(), without.values.size());
  for (size_t i = 0; i < with.values.size(); ++i) {
    EXPECT_NEAR(with.values[i], without.values[i], 1e-9 * std::abs(without.values[i]));
  }
  // Reproducible bit for bit with the cache (on two threads).
  const Solved again = Solve(true, true);
  EXPECT_EQ(again.summary.cost_history, with.summary.cost_history);
  EXPECT_EQ(again.values, with.values);
  // The fit moved (the start is 50 % off) through several accepted steps.
  EXPECT_GE(without.summary.successful_steps, 3);
  EXPECT_LT(without.summary.final_cost, 0.5 * without.summary.initial_cost);
  EXPECT_EQ(without.hits, 0);
  // Each accepted candidate had its gradient evaluated by the line search (unless the search
  // gave up and Ceres took the full step): the candidate's cost and then its Jacobian are
  // copied, for each of the two experiments. Every copy replaces one simulation.
  const int experiments = 2;
  EXPECT_LE(with.jet_simulations,
            without.jet_simulations - experiments * (without.summary.successful_steps - 1));
  EXPECT_LE(with.simulations,
            without.simulations - experiments * (without.summary.successful_steps - 1));
  EXPECT_EQ(with.jet_simulations + with.simulations + with.hits,
            without.jet_simulations + without.simulations);
  std::printf("bounded: %d accepted steps; Jet simulations %ld -> %ld, residual-only %ld -> %ld\n",
              without.summary.successful_steps, without.jet_simulations, with.jet_simulations,
              without.simulations, with.simulations);
}

TEST(EvaluationCache, UnboundedSolveIsBitIdentical) {
  const Solved without = Solve(false, false), with = Solve(true, false);
  ASSERT_TRUE(without.summary.usable && with.summary.usable);
  ExpectSameSolve(with, without);
  EXPECT_GE(without.summary.successful_steps, 3);
  // Without bounds no line search: a candidate's cost is evaluated on doubles and only an
  // accepted point's Jacobian on Jets, so the problem keeps no cache (output_error_problem.cc).
  EXPECT_EQ(with.hits, 0);
  EXPECT_LE(with.jet_simulations, without.jet_simulations);
  EXPECT_EQ(with.jet_simulations + with.simulations + with.hits,
            without.jet_simulations + without.simulations);
}

// An entry is not reused once the data's weights change or other blocks are held constant:
// both evaluations equal those of a problem without the cache.
TEST(EvaluationCache, WeightsAndConstantBlocksInvalidate) {
  const auto model = nomoto::MakeFirstOrderHandle();
  const std::vector<Experiment> runs = {NorrbinRun(*model, 60.0, 3, "run")};
  const std::vector<ParameterSpec> specs = {Spec("T", 30.0, 1.0, 200.0),
                                            Spec("K", 0.1, 0.001, 1.0)};
  std::string error;
  OutputErrorOptions cached, plain;
  plain.evaluation_cache = false;
  auto a = OutputErrorProblem::Create(model.get(), runs, specs, cached, &error);
  auto b = OutputErrorProblem::Create(model.get(), runs, specs, plain, &error);
  ASSERT_NE(a, nullptr) << error;
  ASSERT_NE(b, nullptr) << error;
  auto evaluate = [](OutputErrorProblem* p, std::vector<double>* residuals,
                     std::vector<double>* jacobian) {
    double cost = 0.0;
    ceres::CRSMatrix crs;
    EXPECT_TRUE(
        p->problem()->Evaluate(ceres::Problem::EvaluateOptions(), &cost, residuals, nullptr, &crs));
    *jacobian = crs.values;
  };
  std::vector<double> ra, rb, ja, jb;
  evaluate(a.get(), &ra, &ja);
  evaluate(a.get(), &ra, &ja);
  EXPECT_EQ(a->evaluation_counts().hits, 1);
  evaluate(b.get(), &rb, &jb);
  EXPECT_EQ(ra, rb);
  EXPECT_EQ(ja, jb);

  a->SetChannelWeights({2.0, 1.0});
  b->SetChannelWeights({2.0, 1.0});
  evaluate(a.get(), &ra, &ja);
  evaluate(b.get(), &rb, &jb);
  EXPECT_EQ(a->evaluation_counts().hits, 1);
  EXPECT_EQ(ra, rb);
  EXPECT_EQ(ja, jb);

  // K held: one Jacobian column fewer, a new simulation.
  for (OutputErrorProblem* p : {a.get(), b.get()}) {
    p->problem()->SetParameterBlockConstant(p->variables()[1].block);
  }
  evaluate(a.get(), &ra, &ja);
  evaluate(b.get(), &rb, &jb);
  EXPECT_EQ(a->evaluation_counts().hits, 1);
  EXPECT_EQ(ja.size(), ra.size());
  EXPECT_EQ(ra, rb);
  EXPECT_EQ(ja, jb);

  // Released caches are filled again.
  a->ReleaseEvaluationCaches();
  evaluate(a.get(), &ra, &ja);
  evaluate(a.get(), &ra, &ja);
  EXPECT_EQ(a->evaluation_counts().hits, 2);
  EXPECT_EQ(ja, jb);
}

}  // namespace evaluation_cache_test
}  // namespace vesselid

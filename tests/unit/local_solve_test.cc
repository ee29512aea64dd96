// The local solve's stall stop (LocalSolveOptions::stall_window, stall_tolerance): it ends a
// solve whose last iterations together gain less than the tolerance, successfully, at the
// best point reached, and not before.
#include "engine/solve/local_solve.h"

#include <algorithm>

#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace local_solve_test {

// First-order Nomoto from a start far off (T 8x, K a third), so the solve takes a while.
std::unique_ptr<OutputErrorProblem> FarStart(const ModelHandle& model) {
  std::vector<Experiment> runs = {testing::MakeExperiment(
      model, {2.0, -0.17, 0.0}, testing::ShortLoop(20.0, 1), Interpolation::kCubic, "a")};
  ParameterSpec t, k;
  t.name = "T", t.start = 16.0, t.lower = 0.1, t.upper = 50.0;
  k.name = "K", k.start = -0.05, k.lower = -1.0, k.upper = -0.001;
  std::string error;
  auto problem = OutputErrorProblem::Create(&model, runs, {t, k}, {}, &error);
  EXPECT_NE(problem, nullptr) << error;
  return problem;
}

// K of the wrong sign from T = 2 s (truth T = 20 s, K = 0.1): from radius 1, Levenberg-
// Marquardt's steps toward T < 0 fail and it crawls near that edge; the solve from the start
// again at radius 1e4 converges, and its lower cost is kept.
TEST(LocalSolve, ACrawlFromRadiusOneIsSolvedAgainNearlyGaussNewton) {
  auto model = nomoto::MakeFirstOrderHandle();
  nomoto::ClosedLoopOptions loop = testing::ShortLoop(80.0, 1);
  loop.duration = 600.0;
  loop.sample_time = 0.5;
  std::vector<Experiment> runs = {
      testing::MakeExperiment(*model, {20.0, 0.1, 0.0}, loop, Interpolation::kCubic, "a")};
  ParameterSpec t, k;
  t.name = "T", t.start = 2.0, t.lower = 0.1, t.upper = 1000.0;
  k.name = "K", k.start = -1.0, k.lower = -5.0, k.upper = 5.0;
  std::string error;
  auto problem = OutputErrorProblem::Create(model.get(), runs, {t, k}, {}, &error);
  ASSERT_NE(problem, nullptr) << error;
  LocalSolveOptions options;
  LocalSolveSummary summary;
  ASSERT_TRUE(RunLocalSolve(options, problem.get(), &summary)) << summary.message;
  EXPECT_EQ(summary.termination, "CONVERGENCE");
  EXPECT_NE(summary.message.find("from the start again at radius 1e4"), std::string::npos)
      << summary.message;
  EXPECT_GT(summary.iterations, options.max_iterations);  // the crawl's, then the retry's
  for (const Variable& v : problem->variables()) {
    if (v.name == "T") EXPECT_NEAR(v.value(), 20.0, 0.01);
    if (v.name == "K") EXPECT_NEAR(v.value(), 0.1, 1e-4);
  }
}

TEST(LocalSolve, StallStopEndsACrawlAtItsBestPoint) {
  auto model = nomoto::MakeFirstOrderHandle();
  auto full = FarStart(*model);
  LocalSolveOptions options;
  options.trust_region = TrustRegion::kLevenbergMarquardt;
  options.initial_radius = 1e4;  // nearly Gauss-Newton first steps, then a crawl: > 6 iterations
  LocalSolveSummary converged;
  ASSERT_TRUE(RunLocalSolve(options, full.get(), &converged)) << converged.message;
  EXPECT_EQ(converged.termination, "CONVERGENCE");
  ASSERT_GT(converged.iterations, 6);

  // A window of 2 iterations that must gain half the cost: stops as soon as two iterations
  // together gain less, which a converging solve reaches well before its tolerances.
  auto stalled = FarStart(*model);
  options.stall_window = 2;
  options.stall_tolerance = 0.5;
  LocalSolveSummary summary;
  ASSERT_TRUE(RunLocalSolve(options, stalled.get(), &summary)) << summary.message;
  EXPECT_EQ(summary.termination, "USER_SUCCESS");
  EXPECT_LT(summary.iterations, converged.iterations);
  const std::vector<double>& h = summary.cost_history;
  ASSERT_EQ(static_cast<int>(h.size()), summary.iterations + 1);
  ASSERT_GT(h.size(), 2u);
  // Stopped at the first iteration where the best cost gained less than half over two.
  auto best = [&](size_t i) { return *std::min_element(h.begin(), h.begin() + i + 1); };
  const size_t last = h.size() - 1;
  EXPECT_LT(best(last - 2) - best(last), 0.5 * best(last - 2));
  for (size_t i = 2; i < last; ++i) EXPECT_GE(best(i - 2) - best(i), 0.5 * best(i - 2)) << i;
  // The values left are those of the best iteration.
  double cost = 0.0;
  ASSERT_TRUE(stalled->Cost(&cost));
  EXPECT_NEAR(cost, best(last), 1e-12 * best(last));
  EXPECT_GT(cost, converged.final_cost);

  options.stall_window = -1;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("stall_window"), std::string::npos);
}

// A residual of 0 on T whose derivative cannot be evaluated below T = 3 (the truth is 2; the
// block holds T over its scale): as a simulation that runs in doubles but not in Jets at a
// step the solver accepts.
class NoDerivativeBelow : public ceres::SizedCostFunction<1, 1> {
 public:
  explicit NoDerivativeBelow(double block_threshold) : threshold_(block_threshold) {}
  bool Evaluate(double const* const* x, double* residual, double** jacobians) const override {
    residual[0] = 0.0;
    if (jacobians == nullptr || jacobians[0] == nullptr) return true;
    jacobians[0][0] = 0.0;
    return x[0][0] >= threshold_;
  }

 private:
  double threshold_;
};

// The far start with NoDerivativeBelow on T at T = 3; T's variable (nullptr if none).
const Variable* WithoutDerivativeBelow3(OutputErrorProblem* problem) {
  for (const Variable& v : problem->variables()) {
    if (v.name != "T") continue;
    const double scale = *v.block / v.value();
    problem->problem()->AddResidualBlock(new NoDerivativeBelow(3.0 * scale), nullptr, v.block);
    return &v;
  }
  return nullptr;
}

TEST(LocalSolve, AStepWithoutDerivativesEndsTheSolveAtTheLastIterate) {
  auto model = nomoto::MakeFirstOrderHandle();
  auto problem = FarStart(*model);
  const Variable* t = WithoutDerivativeBelow3(problem.get());
  ASSERT_NE(t, nullptr);
  LocalSolveOptions options;
  // Ceres' minimiser (a named linear solver): it evaluates a candidate's cost before its
  // derivatives.
  options.trust_region = TrustRegion::kLevenbergMarquardt;
  options.linear_solver = ceres::DENSE_NORMAL_CHOLESKY;
  LocalSolveSummary summary;
  ASSERT_TRUE(RunLocalSolve(options, problem.get(), &summary)) << summary.message;
  EXPECT_EQ(summary.termination, kStoppedAtFailedStep);
  EXPECT_NE(summary.message.find("keeps the last iterate"), std::string::npos) << summary.message;
  EXPECT_GE(t->value(), 3.0);
  EXPECT_LT(t->value(), 16.0);  // it made progress before the step
  double cost = 0.0;
  ASSERT_TRUE(problem->Cost(&cost));
  EXPECT_DOUBLE_EQ(cost, summary.final_cost);
  EXPECT_LT(cost, summary.initial_cost);
}

// The engine's own regions (the reflective one, and Levenberg-Marquardt on the normal
// equations, the default) evaluate each trial point with its derivatives: one they cannot
// differentiate is a rejected step, and the solve goes on with a shorter one, ending as near
// the truth as the derivatives allow.
TEST(LocalSolve, DenseRegionsShortenAStepWithoutDerivatives) {
  for (TrustRegion method : {TrustRegion::kReflective, TrustRegion::kLevenbergMarquardt}) {
    SCOPED_TRACE(TrustRegionToString(method));
    auto model = nomoto::MakeFirstOrderHandle();
    auto problem = FarStart(*model);
    const Variable* t = WithoutDerivativeBelow3(problem.get());
    ASSERT_NE(t, nullptr);
    LocalSolveOptions options;
    options.trust_region = method;
    LocalSolveSummary summary;
    ASSERT_TRUE(RunLocalSolve(options, problem.get(), &summary)) << summary.message;
    EXPECT_GT(summary.unsuccessful_steps, 0);
    EXPECT_GE(t->value(), 3.0);
    EXPECT_LT(t->value(), 3.1);
    double cost = 0.0;
    ASSERT_TRUE(problem->Cost(&cost));
    EXPECT_DOUBLE_EQ(cost, summary.final_cost);
    // Levenberg-Marquardt's steps keep a component below T = 3 as its radius shrinks, and it
    // stops on the step length with T on the threshold (cost 0.24x the start's); the
    // reflective region's scaling shortens the step in T alone and goes on in K.
    EXPECT_LT(cost, (method == TrustRegion::kReflective ? 0.1 : 0.3) * summary.initial_cost)
        << summary.message;
  }
}

// The stall check, the progress and the iteration count work alike on the reflective region:
// its iterations are its trial points, each reported once.
TEST(LocalSolve, ReflectiveReportsEachTrialAndStopsOnAStall) {
  auto model = nomoto::MakeFirstOrderHandle();
  auto full = FarStart(*model);
  LocalSolveOptions options;
  options.trust_region = TrustRegion::kReflective;
  std::vector<int> reported;
  options.progress = [&](const SolveProgress& p) { reported.push_back(p.iteration); };
  LocalSolveSummary converged;
  ASSERT_TRUE(RunLocalSolve(options, full.get(), &converged)) << converged.message;
  EXPECT_EQ(converged.termination, "CONVERGENCE");
  ASSERT_EQ(static_cast<int>(converged.cost_history.size()), converged.iterations + 1);
  // Iteration 0 the start, as Ceres reports it (and counts it a successful step).
  ASSERT_EQ(static_cast<int>(reported.size()), converged.iterations + 1);
  for (size_t i = 0; i < reported.size(); ++i) EXPECT_EQ(reported[i], static_cast<int>(i));
  EXPECT_EQ(converged.successful_steps + converged.unsuccessful_steps, converged.iterations + 1);
  // Each trial evaluates residuals and Jacobian once: iterations + 1 evaluations.
  EXPECT_EQ(converged.jacobian_evaluations, converged.iterations + 1);

  auto stalled = FarStart(*model);
  options.stall_window = 1;
  options.stall_tolerance = 0.9;
  LocalSolveSummary summary;
  ASSERT_TRUE(RunLocalSolve(options, stalled.get(), &summary)) << summary.message;
  EXPECT_EQ(summary.termination, "USER_SUCCESS");
  EXPECT_LT(summary.iterations, converged.iterations);
  double cost = 0.0;
  ASSERT_TRUE(stalled->Cost(&cost));
  EXPECT_DOUBLE_EQ(cost, summary.final_cost);
}

}  // namespace local_solve_test
}  // namespace vesselid

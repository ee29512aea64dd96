// Levenberg-Marquardt on the normal equations: on problems whose solutions are known, and
// step for step against Ceres' own Levenberg-Marquardt where Ceres takes no line search
// (no bounds).
#include "engine/solve/levenberg_marquardt.h"

#include <cmath>
#include <limits>
#include <vector>

#include "ceres/ceres.h"
#include "gtest/gtest.h"
#include "tests/support/dense_problems.h"

namespace vesselid {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using testing::Linear;
using testing::Normal;
using testing::Rosenbrock;
using testing::Unbounded;
using testing::kInfinity;

TEST(LevenbergMarquardt, SolvesLinearLeastSquares) {
  MatrixXd a(4, 2);
  a << 1, 0, 0, 2, 1, 1, 3, -1;
  VectorXd b(4);
  b << 1, 2, 3, 4;
  const VectorXd exact = a.colPivHouseholderQr().solve(b);
  VectorXd x(2);
  x << 0.1, 0.1;
  const DenseSolveSummary s =
      SolveLevenbergMarquardt({}, Linear(a, b), Unbounded(2, -1), Unbounded(2, 1), nullptr, &x);
  EXPECT_EQ(s.end, DenseSolveSummary::End::kConvergence) << s.message;
  EXPECT_LT((x - exact).norm(), 1e-10);
  EXPECT_LE(s.evaluations, 4);  // the first step (radius 1e4) is nearly Gauss-Newton's
}

struct RosenbrockResidual {
  template <typename T>
  bool operator()(const T* x, T* f) const {
    f[0] = 10.0 * (x[1] - x[0] * x[0]);
    f[1] = 1.0 - x[0];
    return true;
  }
};

TEST(LevenbergMarquardt, TakesCeresStepsWhereCeresTakesNoLineSearch) {
  double start[2] = {-1.2, 1.0};
  ceres::Problem problem;
  problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<RosenbrockResidual, 2, 2>(new RosenbrockResidual), nullptr,
      start);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  options.function_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.gradient_tolerance = 1e-14;
  ceres::Solver::Summary ceres_summary;
  ceres::Solve(options, &problem, &ceres_summary);
  std::vector<double> ceres_costs;
  std::vector<bool> ceres_accepted;
  for (const ceres::IterationSummary& it : ceres_summary.iterations) {
    ceres_costs.push_back(it.cost);
    ceres_accepted.push_back(it.step_is_successful);
  }
  std::vector<double> costs;
  std::vector<bool> accepted;
  VectorXd x(2);
  x << -1.2, 1.0;
  const DenseSolveSummary s = SolveLevenbergMarquardt(
      {}, Rosenbrock, Unbounded(2, -1), Unbounded(2, 1),
      [&](int, bool ok, double cost, const VectorXd&) {
        costs.push_back(cost);
        accepted.push_back(ok);
        return 0;
      },
      &x);
  EXPECT_EQ(s.end, DenseSolveSummary::End::kConvergence) << s.message;
  EXPECT_NEAR(x[0], 1.0, 1e-8);
  EXPECT_NEAR(start[0], 1.0, 1e-8);
  // The same trial points: Ceres counts the start as a successful step, as the callback does.
  ASSERT_GT(ceres_costs.size(), 10u);
  const size_t common = std::min(costs.size(), ceres_costs.size());
  EXPECT_GE(common + 2, ceres_costs.size());
  for (size_t i = 0; i < common; ++i) {
    EXPECT_EQ(accepted[i], ceres_accepted[i]) << "trial " << i;
    // (Ceres reports a rejected trial's own cost; the callback the iterate's.)
    if (accepted[i] && ceres_accepted[i]) {
      EXPECT_NEAR(costs[i], ceres_costs[i], 1e-9 * ceres_costs[i] + 1e-20) << "trial " << i;
    }
  }
}

TEST(LevenbergMarquardt, HoldsABindingBoundAndReachesTheOptimumOnIt) {
  // With x0 <= 0.5 the minimum is on the bound: x = (0.5, 0.25), cost 1/8.
  VectorXd x(2), upper(2);
  x << -1.2, 1.0;
  upper << 0.5, kInfinity;
  const DenseSolveSummary s =
      SolveLevenbergMarquardt({}, Rosenbrock, Unbounded(2, -1), upper, nullptr, &x);
  EXPECT_EQ(s.end, DenseSolveSummary::End::kConvergence) << s.message;
  EXPECT_EQ(x[0], 0.5);  // projected onto the bound, and held there
  EXPECT_NEAR(x[1], 0.25, 1e-8);
  EXPECT_NEAR(s.final_cost, 0.125, 1e-10);
  EXPECT_LT(s.evaluations, 60);
}

TEST(LevenbergMarquardt, ProjectsAnInfeasibleStart) {
  const MatrixXd a = MatrixXd::Identity(2, 2);
  VectorXd b(2), lower(2), x(2);
  b << -1, 2;
  lower << 0, -kInfinity;
  x << -3, 0;
  const DenseSolveSummary s =
      SolveLevenbergMarquardt({}, Linear(a, b), lower, Unbounded(2, 1), nullptr, &x);
  EXPECT_EQ(s.end, DenseSolveSummary::End::kConvergence) << s.message;
  EXPECT_EQ(x[0], 0.0);
  EXPECT_NEAR(x[1], 2.0, 1e-7);
}

}  // namespace
}  // namespace vesselid

// The reflective trust region on problems whose solutions are known: linear least squares
// with and without an active bound, Rosenbrock's valley with and without a bound across it,
// (what both dense regions do alike: dense_trust_region_test.cc).
#include "engine/solve/reflective_trust_region.h"

#include <cmath>
#include <limits>

#include "gtest/gtest.h"
#include "tests/support/dense_problems.h"

namespace vesselid {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using testing::kInfinity;

using testing::Linear;
using testing::Normal;
using testing::Rosenbrock;
using testing::Unbounded;

TEST(ReflectiveTrustRegion, SolvesLinearLeastSquares) {
  MatrixXd a(4, 2);
  a << 1, 0, 0, 2, 1, 1, 3, -1;
  VectorXd b(4);
  b << 1, 2, 3, 4;
  const VectorXd exact = a.colPivHouseholderQr().solve(b);
  VectorXd x = VectorXd::Zero(2);
  x << 0.1, 0.1;
  const DenseSolveSummary s =
      SolveReflective({}, Linear(a, b), Unbounded(2, -1), Unbounded(2, 1), nullptr, &x);
  EXPECT_EQ(s.end, DenseSolveSummary::End::kConvergence) << s.message;
  EXPECT_LT((x - exact).norm(), 1e-10);
  EXPECT_LE(s.evaluations, 8);  // the region doubles from |x0| = 0.14 to the solution
}

TEST(ReflectiveTrustRegion, EndsOnAnActiveBoundFromInside) {
  // min |x - (-1, 2)| with x0 >= 0: x = (0, 2), reached from inside (x0 > 0 throughout).
  const MatrixXd a = MatrixXd::Identity(2, 2);
  VectorXd b(2), lower(2), x(2);
  b << -1, 2;
  lower << 0, -kInfinity;
  x << 3, 0;
  bool inside = true;
  const DenseSolveSummary s = SolveReflective(
      {}, Linear(a, b), lower, Unbounded(2, 1),
      [&](int, bool, double, const VectorXd& at) {
        inside = inside && at[0] > 0.0;
        return 0;
      },
      &x);
  EXPECT_NE(s.end, DenseSolveSummary::End::kNoConvergence) << s.message;
  EXPECT_TRUE(inside);
  EXPECT_GT(x[0], 0.0);
  EXPECT_LT(x[0], 1e-6);
  EXPECT_NEAR(x[1], 2.0, 1e-8);
}

TEST(ReflectiveTrustRegion, FollowsRosenbrocksValley) {
  VectorXd x(2);
  x << -1.2, 1.0;
  const DenseSolveSummary s =
      SolveReflective({}, Rosenbrock, Unbounded(2, -1), Unbounded(2, 1), nullptr, &x);
  EXPECT_EQ(s.end, DenseSolveSummary::End::kConvergence) << s.message;
  EXPECT_NEAR(x[0], 1.0, 1e-8);
  EXPECT_NEAR(x[1], 1.0, 1e-8);
  EXPECT_LT(s.evaluations, 60);
  EXPECT_GT(s.accepted, 5);
}

TEST(ReflectiveTrustRegion, FollowsTheValleyInTheUnknownsAsGiven) {
  VectorXd x(2);
  x << -1.2, 1.0;
  DenseSolveOptions options;
  options.jacobian_scaling = false;
  const DenseSolveSummary s =
      SolveReflective(options, Rosenbrock, Unbounded(2, -1), Unbounded(2, 1), nullptr, &x);
  EXPECT_EQ(s.end, DenseSolveSummary::End::kConvergence) << s.message;
  EXPECT_NEAR(x[0], 1.0, 1e-8);
  EXPECT_NEAR(x[1], 1.0, 1e-8);
}

TEST(ReflectiveTrustRegion, StopsAtABoundAcrossTheValley) {
  // With x0 <= 0.5 the minimum is on the bound: x = (0.5, 0.25), cost 1/8.
  VectorXd x(2), upper(2);
  x << -1.2, 1.0;
  upper << 0.5, kInfinity;
  const DenseSolveSummary s = SolveReflective({}, Rosenbrock, Unbounded(2, -1), upper, nullptr, &x);
  EXPECT_NE(s.end, DenseSolveSummary::End::kNoConvergence) << s.message;
  EXPECT_LE(x[0], 0.5);
  EXPECT_NEAR(x[0], 0.5, 1e-6);
  EXPECT_NEAR(x[1], 0.25, 1e-6);
  EXPECT_NEAR(s.final_cost, 0.125, 1e-6);
}

}  // namespace
}  // namespace vesselid

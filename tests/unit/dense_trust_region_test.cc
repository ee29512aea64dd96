// What both of the engine's dense trust regions (dense_trust_region.h) do alike: a region
// whose residuals cannot be evaluated shortens the steps, a callback stops or abandons the
// solve, and a start that cannot be evaluated fails.
#include "engine/solve/dense_trust_region.h"

#include "engine/solve/levenberg_marquardt.h"
#include "engine/solve/reflective_trust_region.h"
#include "gtest/gtest.h"
#include "tests/support/dense_problems.h"

namespace vesselid {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using testing::Normal;
using testing::Rosenbrock;
using testing::Unbounded;

using DenseSolver = DenseSolveSummary (*)(const DenseSolveOptions&, const NormalEquationsFunction&,
                                          const VectorXd&, const VectorXd&, const TrialCallback&,
                                          VectorXd*);

class DenseTrustRegion : public ::testing::TestWithParam<DenseSolver> {};

TEST_P(DenseTrustRegion, ShortensStepsWhoseResidualsCannotBeEvaluated) {
  // f = x - 2, not evaluable beyond 1.5 (a simulation that diverges): the solve approaches
  // 1.5 with shorter and shorter steps and never leaves the evaluable region.
  const NormalEquationsFunction f = [](const VectorXd& x, NormalEquations* out) {
    if (x[0] > 1.5) return false;
    Normal(x.array() - 2.0, MatrixXd::Identity(1, 1), out);
    return true;
  };
  VectorXd x = VectorXd::Zero(1);
  DenseSolveOptions options;
  options.max_evaluations = 100;
  const DenseSolveSummary s = GetParam()(options, f, Unbounded(1, -1), Unbounded(1, 1), nullptr, &x);
  EXPECT_GT(s.rejected, 0);
  EXPECT_LE(x[0], 1.5);
  EXPECT_GT(x[0], 1.4);
  EXPECT_EQ(s.evaluations, s.accepted + s.rejected + 1);
}

TEST_P(DenseTrustRegion, ACallbackStopsOrAbandons) {
  VectorXd x(2);
  x << -1.2, 1.0;
  const DenseSolveSummary abandoned = GetParam()(
      {}, Rosenbrock, Unbounded(2, -1), Unbounded(2, 1),
      [](int trial, bool, double, const VectorXd&) { return trial == 3 ? -1 : 0; }, &x);
  EXPECT_EQ(abandoned.end, DenseSolveSummary::End::kUserFailure);
  EXPECT_EQ(abandoned.evaluations, 4);
  x << -1.2, 1.0;
  const DenseSolveSummary stopped = GetParam()(
      {}, Rosenbrock, Unbounded(2, -1), Unbounded(2, 1),
      [](int trial, bool, double, const VectorXd&) { return trial == 2 ? 1 : 0; }, &x);
  EXPECT_EQ(stopped.end, DenseSolveSummary::End::kUserSuccess);
}

TEST_P(DenseTrustRegion, AStartThatCannotBeEvaluatedFails) {
  const NormalEquationsFunction f = [](const VectorXd&, NormalEquations*) { return false; };
  VectorXd x = VectorXd::Ones(1);
  const DenseSolveSummary s = GetParam()({}, f, Unbounded(1, -1), Unbounded(1, 1), nullptr, &x);
  EXPECT_EQ(s.end, DenseSolveSummary::End::kFailure);
  EXPECT_EQ(s.initial_cost, -1.0);
}

INSTANTIATE_TEST_SUITE_P(Methods, DenseTrustRegion,
                         ::testing::Values(&SolveReflective, &SolveLevenbergMarquardt),
                         [](const ::testing::TestParamInfo<DenseSolver>& info) {
                           return info.index == 0 ? "reflective" : "levenberg_marquardt";
                         });

}  // namespace
}  // namespace vesselid

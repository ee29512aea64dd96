// The solution Jacobian evaluated once by the stage and shared by the HAC covariance and the
// local analysis gives the figures each computes from its own evaluation; on a first-order
// Nomoto model fitted to noisy closed-loop second-order data (the model does not match), two
// experiments with free initial headings and their priors (rows after the data rows).
#include "engine/solve/solution_jacobian.h"

#include <cmath>

#include "ceres/covariance.h"
#include "engine/base/memory_budget.h"
#include "engine/solve/covariance.h"
#include "engine/solve/stage.h"
#include "gtest/gtest.h"
#include "problems/nomoto/handles.h"
#include "tests/support/nomoto_data.h"

namespace vesselid {
namespace solution_jacobian_test {

nomoto::ClosedLoopOptions NoisyLoop(unsigned seed) {
  nomoto::ClosedLoopOptions loop;
  loop.controller_gain = 0.7;
  loop.duration = 120.0;
  loop.sample_time = 0.05;
  loop.excitation.type = nomoto::Excitation::Type::kMultisine;
  loop.excitation.amplitude = 25.0 * M_PI / 180.0;
  loop.excitation.periods = {60.0, 23.0, 11.0, 5.0};
  loop.heading_noise = 0.2 * M_PI / 180.0;
  loop.seed = seed;
  return loop;
}

// A first-order model of two noisy second-order closed-loop runs with free initial headings
// and their priors (rows after the data rows).
class SolutionJacobianTest : public ::testing::Test {
 protected:
  void SetUp() override {
    second_ = nomoto::MakeSecondOrderHandle();
    first_ = nomoto::MakeFirstOrderHandle();
    const std::vector<double> truth = {2.0875, 0.3179, 0.1830, -0.1724, 0.0};
    // Simulated by the second-order loop, read by the first-order model.
    std::vector<Experiment> runs;
    for (unsigned seed : {3u, 4u}) {
      Trajectory trajectory;
      std::string error;
      ASSERT_TRUE(nomoto::SimulateClosedLoop(*second_, truth, NoisyLoop(seed), &trajectory, &error))
          << error;
      trajectory.source = "run" + std::to_string(seed);
      ExperimentSpec spec;
      spec.name = trajectory.source;
      spec.inputs = {{"delta", "delta"}};
      spec.outputs = {{"psi", "psi"}};
      Experiment e;
      ASSERT_TRUE(BuildExperiment(spec, trajectory, first_->info(), ExperimentOptions(), &e, &error))
          << error;
      runs.push_back(std::move(e));
    }
    ParameterSpec t{}, k{};
    t.name = "T";
    t.start = 3.0;
    k.name = "K";
    k.start = -0.1;
    OutputErrorOptions options;
    options.free_initial_states = {"psi"};
    options.prior.apply = InitialStatePrior::Apply::kAll;
    std::string error;
    problem_ = OutputErrorProblem::Create(first_.get(), runs, {t, k}, options, &error);
    ASSERT_NE(problem_, nullptr) << error;
  }

  std::unique_ptr<ModelHandle> second_, first_;
  std::unique_ptr<OutputErrorProblem> problem_;
};

TEST_F(SolutionJacobianTest, SharedEvaluationGivesTheAnalysesTheirOwnFigures) {
  OutputErrorProblem* problem = problem_.get();
  StageSummary summary;
  ASSERT_TRUE(RunStage(StageOptions(), problem, &summary)) << summary.message;
  ASSERT_TRUE(summary.uncertainty.available) << summary.uncertainty.message;
  ASSERT_TRUE(summary.analysis.available) << summary.analysis.message;

  SolutionJacobian solution;
  ASSERT_TRUE(EvaluateSolutionJacobian(problem, 1, &solution));
  EXPECT_EQ(solution.data_rows, problem->num_residuals());
  EXPECT_EQ(solution.variables.size(), 4u);  // T, K, two initial headings
  EXPECT_GE(solution.jacobian.num_rows, solution.data_rows);
  double cost = 0.0;
  ASSERT_TRUE(problem->Cost(&cost));
  EXPECT_LE(solution.DataCost(), cost * (1 + 1e-12));  // priors add to the problem's cost

  // Each analysis on its own evaluation.
  Uncertainty hessian, hac;
  ASSERT_TRUE(ComputeUncertainty(problem, summary.local().final_cost, &hessian));
  ASSERT_TRUE(ComputeHacCovariance(HacOptions(), problem, hessian, &hac)) << hac.message;
  LocalAnalysis alone;
  ASSERT_TRUE(ComputeLocalAnalysis(LocalAnalysisOptions(), problem, &alone));

  const Uncertainty& staged = summary.uncertainty;
  ASSERT_EQ(staged.variables, hac.variables);
  for (size_t i = 0; i < hac.variables.size(); ++i) {
    const double reference =
        staged.method == "sandwich_hac" ? hac.std_errors[i] : hessian.std_errors[i];
    EXPECT_NEAR(staged.std_errors[i], reference, 1e-9 * reference) << i;
  }
  const LocalAnalysis& shared = summary.analysis;
  ASSERT_EQ(shared.std_errors.size(), alone.std_errors.size());
  EXPECT_EQ(shared.profiled, 2);
  EXPECT_NEAR(shared.residual_variance, alone.residual_variance, 1e-9 * alone.residual_variance);
  for (size_t i = 0; i < alone.std_errors.size(); ++i) {
    EXPECT_NEAR(shared.std_errors[i], alone.std_errors[i], 1e-9 * alone.std_errors[i]);
  }
  EXPECT_LT((shared.information - alone.information).norm(), 1e-9 * alone.information.norm());
}

// The Hessian covariance from the triangular factor of the shared Jacobian equals Ceres'
// own (sparse QR) over every free variable, the initial headings included.
TEST_F(SolutionJacobianTest, HessianCovarianceMatchesCeresSparseQr) {
  OutputErrorProblem* problem = problem_.get();
  StageSummary summary;
  ASSERT_TRUE(RunStage(StageOptions(), problem, &summary)) << summary.message;
  SolutionJacobian solution;
  ASSERT_TRUE(EvaluateSolutionJacobian(problem, 1, &solution));
  Uncertainty hessian;
  ASSERT_TRUE(ComputeUncertainty(problem, summary.local().final_cost, &hessian, &solution));
  ASSERT_TRUE(hessian.undetermined.empty());

  std::vector<const double*> blocks;
  for (int index : hessian.variables) blocks.push_back(problem->variables()[index].block);
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::SPARSE_QR;
  ceres::Covariance covariance(options);
  ASSERT_TRUE(covariance.Compute(blocks, problem->problem()));
  const int n = static_cast<int>(blocks.size());
  Eigen::MatrixXd theta(n, n);
  covariance.GetCovarianceMatrix(blocks, theta.data());
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const double sa = problem->variables()[hessian.variables[a]].scale;
      const double sb = problem->variables()[hessian.variables[b]].scale;
      const double expected = hessian.residual_variance * sa * sb * theta(a, b);
      const double size = std::sqrt(hessian.covariance(a, a) * hessian.covariance(b, b));
      EXPECT_NEAR(hessian.covariance(a, b), expected, 1e-8 * size) << a << "," << b;
    }
  }
}

// Over the memory budget for the dense covariance, the covariance by blocks gives the shared
// parameters' covariance and each experiment's initial heading's standard error exactly as the
// dense one does (the inverse of the Schur complement; the rows of R^-1).
TEST_F(SolutionJacobianTest, CovarianceByBlocksMatchesTheDenseOne) {
  OutputErrorProblem* problem = problem_.get();
  StageSummary summary;
  ASSERT_TRUE(RunStage(StageOptions(), problem, &summary)) << summary.message;
  SolutionJacobian solution;
  ASSERT_TRUE(EvaluateSolutionJacobian(problem, 1, &solution));
  const double cost = summary.local().final_cost;
  Uncertainty dense, blocks;
  ASSERT_TRUE(ComputeUncertainty(problem, cost, &dense, &solution));
  ASSERT_EQ(dense.variables.size(), 4u);  // T, K, two initial headings
  ASSERT_TRUE(dense.block_variables.empty());
  {
    // 4 free variables: dense 1 KiB, by blocks 896 bytes.
    ScopedMemoryBudget budget(1000);
    ASSERT_TRUE(ComputeUncertainty(problem, cost, &blocks, &solution)) << blocks.message;
  }
  ASSERT_EQ(blocks.variables.size(), 2u) << blocks.message;
  ASSERT_EQ(blocks.block_variables.size(), 2u);
  EXPECT_NE(blocks.message.find("the covariance of the 2 shared variable(s) only"),
            std::string::npos)
      << blocks.message;
  EXPECT_DOUBLE_EQ(blocks.residual_variance, dense.residual_variance);
  for (int index : dense.variables) {
    const double expected = dense.StdError(index);
    EXPECT_NEAR(blocks.StdError(index), expected, 1e-9 * expected)
        << problem->variables()[index].name;
  }
  // The shared block of the covariance and its correlation.
  for (size_t a = 0; a < blocks.variables.size(); ++a) {
    for (size_t b = 0; b < blocks.variables.size(); ++b) {
      int da = -1, db = -1;
      for (size_t k = 0; k < dense.variables.size(); ++k) {
        if (dense.variables[k] == blocks.variables[a]) da = static_cast<int>(k);
        if (dense.variables[k] == blocks.variables[b]) db = static_cast<int>(k);
      }
      ASSERT_GE(da, 0);
      ASSERT_GE(db, 0);
      const double size = std::sqrt(dense.covariance(da, da) * dense.covariance(db, db));
      EXPECT_NEAR(blocks.covariance(a, b), dense.covariance(da, db), 1e-9 * size);
      EXPECT_NEAR(blocks.correlation(a, b), dense.correlation(da, db), 1e-9);
    }
  }
  // Less than the blocks need: not computed, and the message says so.
  {
    ScopedMemoryBudget budget(100);
    Uncertainty none;
    EXPECT_FALSE(ComputeUncertainty(problem, cost, &none, &solution));
    EXPECT_NE(none.message.find("not computed"), std::string::npos) << none.message;
  }
}

}  // namespace solution_jacobian_test
}  // namespace vesselid

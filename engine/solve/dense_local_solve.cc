#include "engine/solve/dense_local_solve.h"

#include <cmath>
#include <limits>
#include <vector>

#include "engine/solve/levenberg_marquardt.h"
#include "engine/solve/normal_equations.h"
#include "engine/solve/reflective_trust_region.h"

namespace vesselid {
namespace {

// Ceres' getters give +-max double for an unbounded side.
double Bound(double value) {
  constexpr double kHuge = 0.5 * std::numeric_limits<double>::max();
  if (value >= kHuge) return std::numeric_limits<double>::infinity();
  if (value <= -kHuge) return -std::numeric_limits<double>::infinity();
  return value;
}

ceres::TerminationType CeresTermination(DenseSolveSummary::End end) {
  switch (end) {
    case DenseSolveSummary::End::kConvergence:
      return ceres::CONVERGENCE;
    case DenseSolveSummary::End::kNoConvergence:
      return ceres::NO_CONVERGENCE;
    case DenseSolveSummary::End::kUserSuccess:
      return ceres::USER_SUCCESS;
    case DenseSolveSummary::End::kUserFailure:
      return ceres::USER_FAILURE;
    case DenseSolveSummary::End::kFailure:
      return ceres::FAILURE;
  }
  return ceres::FAILURE;
}

// The problem's free, non-constant blocks: the solve's unknowns.
std::vector<double*> Unknowns(OutputErrorProblem* problem) {
  std::vector<double*> unknowns;
  for (const Variable& v : problem->variables()) {
    if (v.free && !problem->problem()->IsParameterBlockConstant(v.block)) {
      unknowns.push_back(v.block);
    }
  }
  return unknowns;
}

}  // namespace

bool CanSolveOnNormalEquations(OutputErrorProblem* problem) {
  return NormalEquationsEvaluator::Handles(*problem->problem());
}

void SolveOnNormalEquations(DenseMethod method, const ceres::Solver::Options& options,
                            OutputErrorProblem* problem, ceres::Solver::Summary* summary) {
  *summary = ceres::Solver::Summary();
  ceres::Problem* ceres_problem = problem->problem();
  const std::vector<double*> unknowns = Unknowns(problem);
  const int n = static_cast<int>(unknowns.size());
  Eigen::VectorXd x(n), lower(n), upper(n);
  for (int i = 0; i < n; ++i) {
    x[i] = *unknowns[i];
    lower[i] = Bound(ceres_problem->GetParameterLowerBound(unknowns[i], 0));
    upper[i] = Bound(ceres_problem->GetParameterUpperBound(unknowns[i], 0));
  }
  auto set = [&](const Eigen::VectorXd& at) {
    for (int i = 0; i < n; ++i) *unknowns[i] = at[i];
  };
  // The cost functions evaluated directly (normal_equations.h): the engine's problems keep
  // their losses inside the experiments' residuals and give every unknown its own block.
  NormalEquationsEvaluator direct(ceres_problem, unknowns, options.num_threads);
  if (!direct.usable()) {
    summary->termination_type = ceres::FAILURE;
    summary->message =
        "the engine's dense trust regions need scalar unknowns and no Ceres loss function";
    return;
  }
  auto function = [&](const Eigen::VectorXd& at, NormalEquations* out) {
    set(at);
    return direct.Evaluate(out);
  };
  auto callback = [&](int trial, bool accepted, double cost, const Eigen::VectorXd& at) {
    set(at);
    ceres::IterationSummary step;
    step.iteration = trial;
    step.cost = cost;
    step.step_is_successful = accepted;
    step.step_is_valid = true;
    summary->iterations.push_back(step);
    for (ceres::IterationCallback* c : options.callbacks) {
      const ceres::CallbackReturnType answer = (*c)(step);
      if (answer == ceres::SOLVER_ABORT) return -1;
      if (answer == ceres::SOLVER_TERMINATE_SUCCESSFULLY) return 1;
    }
    return 0;
  };
  DenseSolveOptions dense;
  dense.max_evaluations = options.max_num_iterations + 1;  // the start's and each step's
  dense.function_tolerance = options.function_tolerance;
  dense.parameter_tolerance = options.parameter_tolerance;
  dense.gradient_tolerance = options.gradient_tolerance;
  dense.max_time_seconds = options.max_solver_time_in_seconds;
  dense.initial_radius = options.initial_trust_region_radius;
  summary->iterations.reserve(options.max_num_iterations + 1);
  const DenseSolveSummary result =
      method == DenseMethod::kReflective
          ? SolveReflective(dense, function, lower, upper, callback, &x)
          : SolveLevenbergMarquardt(dense, function, lower, upper, callback, &x);
  set(x);
  summary->initial_cost = result.initial_cost;
  summary->final_cost = result.final_cost;
  // The final cost as the problem sums it (OutputErrorProblem::Cost), as the other methods
  // report theirs: the same bits as any later evaluation at these values.
  double ordered = 0.0;
  if (result.end != DenseSolveSummary::End::kFailure && !summary->iterations.empty() &&
      problem->Cost(&ordered)) {
    summary->final_cost = ordered;
    summary->iterations.back().cost = ordered;
  }
  summary->termination_type = CeresTermination(result.end);
  summary->message = result.message;
  // Ceres counts its start as a successful step.
  summary->num_successful_steps = result.accepted + (result.initial_cost >= 0.0 ? 1 : 0);
  summary->num_unsuccessful_steps = result.rejected;
  summary->num_residual_evaluations = result.evaluations;
  summary->num_jacobian_evaluations = result.evaluations;
  summary->residual_evaluation_time_in_seconds = 0.0;  // each evaluation forms both
  summary->jacobian_evaluation_time_in_seconds = result.evaluation_seconds;
  summary->linear_solver_time_in_seconds = result.step_seconds;
  summary->total_time_in_seconds = result.total_seconds;
}

}  // namespace vesselid

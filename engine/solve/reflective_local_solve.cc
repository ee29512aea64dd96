#include "engine/solve/reflective_local_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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

ceres::TerminationType CeresTermination(ReflectiveSummary::End end) {
  switch (end) {
    case ReflectiveSummary::End::kConvergence:
      return ceres::CONVERGENCE;
    case ReflectiveSummary::End::kNoConvergence:
      return ceres::NO_CONVERGENCE;
    case ReflectiveSummary::End::kUserSuccess:
      return ceres::USER_SUCCESS;
    case ReflectiveSummary::End::kUserFailure:
      return ceres::USER_FAILURE;
    case ReflectiveSummary::End::kFailure:
      return ceres::FAILURE;
  }
  return ceres::FAILURE;
}

}  // namespace

void SolveReflectiveProblem(const ceres::Solver::Options& options, OutputErrorProblem* problem,
                            ceres::Solver::Summary* summary) {
  *summary = ceres::Solver::Summary();
  ceres::Problem* ceres_problem = problem->problem();
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.num_threads = options.num_threads;
  for (const Variable& v : problem->variables()) {
    if (v.free && !ceres_problem->IsParameterBlockConstant(v.block)) {
      evaluate.parameter_blocks.push_back(v.block);
    }
  }
  const int n = static_cast<int>(evaluate.parameter_blocks.size());
  Eigen::VectorXd x(n), lower(n), upper(n);
  for (int i = 0; i < n; ++i) {
    double* block = evaluate.parameter_blocks[i];
    x[i] = *block;
    lower[i] = Bound(ceres_problem->GetParameterLowerBound(block, 0));
    upper[i] = Bound(ceres_problem->GetParameterUpperBound(block, 0));
  }
  auto set = [&](const Eigen::VectorXd& at) {
    for (int i = 0; i < n; ++i) *evaluate.parameter_blocks[i] = at[i];
  };
  std::vector<double> residuals;
  ceres::CRSMatrix crs;
  // The cost functions evaluated directly (normal_equations.h), or, for a problem with a
  // Ceres loss function, Problem::Evaluate and one pass over its Jacobian's rows. The cost is
  // summed here in the problem's order (the losses are inside the experiments' residuals, so 1/2
  // |f|^2 is the cost), the same on any number of threads.
  NormalEquationsEvaluator direct(ceres_problem, evaluate.parameter_blocks, options.num_threads);
  auto function = [&](const Eigen::VectorXd& at, NormalEquations* out) {
    set(at);
    if (direct.usable()) return direct.Evaluate(out);
    double ceres_cost = 0.0;
    if (!ceres_problem->Evaluate(evaluate, &ceres_cost, &residuals, nullptr, &crs)) return false;
    out->residuals = static_cast<int>(residuals.size());
    out->gradient.setZero(n);
    out->normal.setZero(n, n);
    double sum = 0.0;
    for (int row = 0; row < crs.num_rows; ++row) {
      const double r = residuals[row];
      sum += r * r;
      for (int k = crs.rows[row]; k < crs.rows[row + 1]; ++k) {
        const int i = crs.cols[k];
        const double a = crs.values[k];
        out->gradient[i] += a * r;
        for (int l = k; l < crs.rows[row + 1]; ++l) {
          const int j = crs.cols[l];
          out->normal(std::min(i, j), std::max(i, j)) += a * crs.values[l];
        }
      }
    }
    out->normal.triangularView<Eigen::StrictlyLower>() =
        out->normal.transpose().triangularView<Eigen::StrictlyLower>();
    out->cost = 0.5 * sum;
    return true;
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
  ReflectiveOptions reflective;
  reflective.max_evaluations = options.max_num_iterations + 1;  // the start's and each step's
  reflective.function_tolerance = options.function_tolerance;
  reflective.parameter_tolerance = options.parameter_tolerance;
  reflective.gradient_tolerance = options.gradient_tolerance;
  reflective.max_time_seconds = options.max_solver_time_in_seconds;
  summary->iterations.reserve(options.max_num_iterations + 1);
  const ReflectiveSummary result =
      SolveReflective(reflective, function, lower, upper, callback, &x);
  set(x);
  summary->initial_cost = result.initial_cost;
  summary->final_cost = result.final_cost;
  // The final cost as the problem sums it (OutputErrorProblem::Cost), as the other methods
  // report theirs: the same bits as any later evaluation at these values.
  double ordered = 0.0;
  if (result.end != ReflectiveSummary::End::kFailure && !summary->iterations.empty() &&
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

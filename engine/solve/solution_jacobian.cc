#include "engine/solve/solution_jacobian.h"

#include <algorithm>
#include <unordered_set>

namespace vesselid {

double SolutionJacobian::DataCost() const {
  double sum = 0.0;
  for (int r = 0; r < data_rows; ++r) sum += residuals[r] * residuals[r];
  return 0.5 * sum;
}

bool EvaluateSolutionJacobian(OutputErrorProblem* problem, int num_threads, SolutionJacobian* out) {
  *out = SolutionJacobian();
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.num_threads = std::max(1, num_threads);
  const std::vector<Variable>& variables = problem->variables();
  for (size_t i = 0; i < variables.size(); ++i) {
    if (!variables[i].free) continue;
    out->variables.push_back(static_cast<int>(i));
    evaluate.parameter_blocks.push_back(variables[i].block);
  }
  evaluate.residual_blocks = problem->data_residual_blocks();
  const std::unordered_set<ceres::ResidualBlockId> data(evaluate.residual_blocks.begin(),
                                                        evaluate.residual_blocks.end());
  std::vector<ceres::ResidualBlockId> all;
  problem->problem()->GetResidualBlocks(&all);
  for (ceres::ResidualBlockId id : all) {
    if (data.count(id) == 0) evaluate.residual_blocks.push_back(id);
  }
  if (!problem->problem()->Evaluate(evaluate, nullptr, &out->residuals, nullptr, &out->jacobian)) {
    *out = SolutionJacobian();
    return false;
  }
  out->data_rows = problem->num_residuals();
  return true;
}

}  // namespace vesselid

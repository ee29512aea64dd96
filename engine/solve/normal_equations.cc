#include "engine/solve/normal_equations.h"

#include <map>
#include <utility>

#include "Eigen/Dense"
#include "engine/base/parallel_for.h"

namespace vesselid {

NormalEquationsEvaluator::NormalEquationsEvaluator(ceres::Problem* problem,
                                                   std::vector<double*> unknowns, int threads)
    : unknowns_(static_cast<int>(unknowns.size())), threads_(threads) {
  std::map<const double*, int> column;
  for (int i = 0; i < unknowns_; ++i) column[unknowns[i]] = i;
  std::vector<ceres::ResidualBlockId> ids;
  problem->GetResidualBlocks(&ids);
  for (ceres::ResidualBlockId id : ids) {
    Block block;
    block.cost = problem->GetCostFunctionForResidualBlock(id);
    if (problem->GetLossFunctionForResidualBlock(id) != nullptr) usable_ = false;
    problem->GetParameterBlocksForResidualBlock(id, &block.parameters);
    block.residuals.resize(block.cost->num_residuals());
    block.jacobian.resize(block.parameters.size());
    for (double* p : block.parameters) {
      if (problem->ParameterBlockSize(p) != 1) usable_ = false;
      const auto found = column.find(p);
      block.column.push_back(found == column.end() ? -1 : found->second);
      if (found != column.end())
        block.jacobian[block.column.size() - 1].resize(block.residuals.size());
    }
    blocks_.push_back(std::move(block));
  }
}

bool NormalEquationsEvaluator::Handles(const ceres::Problem& problem) {
  std::vector<ceres::ResidualBlockId> ids;
  problem.GetResidualBlocks(&ids);
  std::vector<double*> parameters;
  for (ceres::ResidualBlockId id : ids) {
    if (problem.GetLossFunctionForResidualBlock(id) != nullptr) return false;
    problem.GetParameterBlocksForResidualBlock(id, &parameters);
    for (double* p : parameters) {
      if (problem.ParameterBlockSize(p) != 1) return false;
    }
  }
  return true;
}

bool NormalEquationsEvaluator::Evaluate(NormalEquations* out) {
  const int n = unknowns_;
  const int count = static_cast<int>(blocks_.size());
  std::vector<Eigen::MatrixXd> normals(count);
  std::vector<Eigen::VectorXd> gradients(count);
  std::vector<double> sums(count, 0.0);
  ParallelFor(count, threads_, [&](int b) {
    Block& block = blocks_[b];
    std::vector<double*> jacobians(block.parameters.size(), nullptr);
    for (size_t j = 0; j < jacobians.size(); ++j) {
      if (block.column[j] >= 0) jacobians[j] = block.jacobian[j].data();
    }
    block.ok =
        block.cost->Evaluate(block.parameters.data(), block.residuals.data(), jacobians.data());
    if (!block.ok) return;
    const Eigen::Map<const Eigen::VectorXd> r(block.residuals.data(), block.residuals.size());
    normals[b].setZero(n, n);
    gradients[b].setZero(n);
    sums[b] = r.squaredNorm();
    for (size_t j = 0; j < jacobians.size(); ++j) {
      const int cj = block.column[j];
      if (cj < 0) continue;
      const Eigen::Map<const Eigen::VectorXd> col_j(jacobians[j], r.size());
      gradients[b][cj] += col_j.dot(r);
      for (size_t k = j; k < jacobians.size(); ++k) {
        const int ck = block.column[k];
        if (ck < 0) continue;
        const Eigen::Map<const Eigen::VectorXd> col_k(jacobians[k], r.size());
        const double value = col_j.dot(col_k);
        normals[b](cj, ck) += value;
        if (ck != cj) normals[b](ck, cj) += value;
      }
    }
  });
  out->gradient.setZero(n);
  out->normal.setZero(n, n);
  out->residuals = 0;
  double sum = 0.0;
  for (int b = 0; b < count; ++b) {
    if (!blocks_[b].ok) return false;
    out->gradient += gradients[b];
    out->normal += normals[b];
    out->residuals += static_cast<int>(blocks_[b].residuals.size());
    sum += sums[b];
  }
  out->cost = 0.5 * sum;
  return true;
}

}  // namespace vesselid

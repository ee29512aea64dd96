// J'J, J'f and the cost of an output-error problem's unknowns, formed straight from its
// residual blocks' cost functions: each block (an experiment, a prior) evaluated with the
// Jacobian columns of the unknowns it uses, on the experiments' threads, its contribution
// formed from those columns (dot products) and the contributions summed in block order, so
// that the result is the same on any number of threads. One pass per evaluation, none of
// Ceres' per-call program and sparse-matrix assembly (Problem::Evaluate).
#pragma once

#include <vector>

#include "ceres/ceres.h"
#include "engine/solve/reflective_trust_region.h"

namespace vesselid {

class NormalEquationsEvaluator {
 public:
  // `unknowns`: the parameter blocks (size 1 each) that are the columns, in order.
  NormalEquationsEvaluator(ceres::Problem* problem, std::vector<double*> unknowns, int threads);

  // False when the problem has what this evaluator does not handle: a Ceres loss function on
  // a residual block, or a parameter block larger than 1. Handles: the same, without forming
  // the evaluator's buffers.
  bool usable() const { return usable_; }
  static bool Handles(const ceres::Problem& problem);

  // At the blocks' current values; false when a block cannot be evaluated.
  bool Evaluate(NormalEquations* out);

 private:
  struct Block {
    const ceres::CostFunction* cost = nullptr;
    std::vector<double*> parameters;
    std::vector<int> column;  // per parameter: its unknown's column, -1 when not an unknown
    std::vector<double> residuals;
    std::vector<std::vector<double>> jacobian;  // per parameter (empty when not an unknown)
    bool ok = false;
  };
  std::vector<Block> blocks_;
  int unknowns_ = 0;
  int threads_ = 1;
  bool usable_ = true;
};

}  // namespace vesselid

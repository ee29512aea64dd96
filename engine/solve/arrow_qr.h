// The triangular factor of a block-arrow Jacobian, without forming it densely.
//
// Columns are shared (group < 0) or belong to one experiment's group (free initial states,
// per-experiment parameters); a row touches the shared columns and at most one group's (rows
// that would join two groups merge them). With the columns permuted group by group and the
// shared ones last, J P = Q R with
//
//   R = [ R_11              R_1p ]
//       [       ...          ... ]
//       [            R_GG   R_Gp ]
//       [                   R_pp ]
//
// Each group's rows are reduced by Householder QR a chunk at a time (R of [R; next rows], so
// memory is one chunk and one group's R); the shared-column rows each group leaves behind
// are stacked with the rows that touch only shared columns and reduced the same way. R^T R =
// P^T J^T J P exactly, and R has J's singular values, so covariance and rank are read off R
// (n x n) as accurately as off J (m x n) itself.
#pragma once

#include <vector>

#include "Eigen/Dense"
#include "ceres/crs_matrix.h"

namespace vesselid {

// R by blocks: each group's R_gg and R_gp, and R_pp, in n (own + shared) numbers per row of
// a group instead of n.
struct ArrowBlocks {
  struct Block {
    std::vector<int> columns;  // the Jacobian columns of the group, in R's order
    Eigen::MatrixXd own;       // R_gg, upper triangular
    Eigen::MatrixXd shared;    // R_gp
  };
  std::vector<Block> blocks;
  std::vector<int> shared_columns;  // in R's order
  Eigen::MatrixXd shared;           // R_pp, upper triangular
};

struct ArrowR {
  Eigen::MatrixXd r;       // n x n upper triangular, in `order`
  std::vector<int> order;  // order[k]: the Jacobian column held in R's column k
};

// `group[c]`: column c's group (< 0: shared). Rows [0, rows) of `jacobian` are used
// (rows < 0: all).
ArrowR ArrowQr(const ceres::CRSMatrix& jacobian, const std::vector<int>& group, int rows = -1);
// The same R by blocks (memory linear in the number of groups).
ArrowBlocks ArrowQrBlocks(const ceres::CRSMatrix& jacobian, const std::vector<int>& group,
                          int rows = -1);

}  // namespace vesselid

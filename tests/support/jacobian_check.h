// Compares a cost function's Jacobian with central finite differences, block by block
// (all blocks of size 1): max |J_fd - J| <= tolerance * max |J_fd| per column.
#pragma once

#include <cmath>
#include <vector>

#include "ceres/ceres.h"
#include "gtest/gtest.h"

namespace vesselid::testing {

// Returns how many columns were compared; columns with no effect must have a zero Jacobian.
inline int ExpectJacobianMatchesFiniteDifferences(const ceres::CostFunction& cost,
                                                  std::vector<double> theta, double tolerance) {
  const int n = static_cast<int>(theta.size());
  const int m = cost.num_residuals();
  std::vector<const double*> blocks;
  for (double& t : theta) blocks.push_back(&t);
  std::vector<std::vector<double>> jacobian(n, std::vector<double>(m));
  std::vector<double*> jacobian_blocks;
  for (auto& column : jacobian) jacobian_blocks.push_back(column.data());
  std::vector<double> residuals(m), plus(m), minus(m);
  EXPECT_TRUE(cost.Evaluate(blocks.data(), residuals.data(), jacobian_blocks.data()));
  int compared = 0;
  for (int j = 0; j < n; ++j) {
    const double saved = theta[j];
    const double h = 1e-6 * std::max(1.0, std::abs(saved));
    theta[j] = saved + h;
    EXPECT_TRUE(cost.Evaluate(blocks.data(), plus.data(), nullptr));
    theta[j] = saved - h;
    EXPECT_TRUE(cost.Evaluate(blocks.data(), minus.data(), nullptr));
    theta[j] = saved;
    double column = 0.0, difference = 0.0;
    for (int i = 0; i < m; ++i) {
      const double fd = (plus[i] - minus[i]) / (2 * h);
      column = std::max(column, std::abs(fd));
      difference = std::max(difference, std::abs(fd - jacobian[j][i]));
    }
    if (column == 0.0) {
      EXPECT_EQ(difference, 0.0) << "block " << j;
      continue;
    }
    ++compared;
    EXPECT_LT(difference, tolerance * column) << "block " << j;
  }
  return compared;
}

}  // namespace vesselid::testing

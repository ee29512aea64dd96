// Small least-squares problems with known solutions, as the engine's dense trust regions
// (engine/solve/dense_trust_region.h) see them: the normal equations of residuals f with
// Jacobian J.
#pragma once

#include <limits>

#include "engine/solve/dense_trust_region.h"

namespace vesselid {
namespace testing {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

inline void Normal(const Eigen::VectorXd& f, const Eigen::MatrixXd& j, NormalEquations* out) {
  out->cost = 0.5 * f.squaredNorm();
  out->gradient = j.transpose() * f;
  out->normal = j.transpose() * j;
  out->residuals = static_cast<int>(f.size());
}

// f = A x - b.
inline NormalEquationsFunction Linear(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  return [a, b](const Eigen::VectorXd& x, NormalEquations* out) {
    Normal(a * x - b, a, out);
    return true;
  };
}

// Rosenbrock's function as residuals: f = (10 (x1 - x0^2), 1 - x0).
inline bool Rosenbrock(const Eigen::VectorXd& x, NormalEquations* out) {
  Eigen::VectorXd f(2);
  Eigen::MatrixXd j(2, 2);
  f << 10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0];
  j << -20.0 * x[0], 10.0, -1.0, 0.0;
  Normal(f, j, out);
  return true;
}

// n bounds at -inf (sign -1) or +inf (sign 1).
inline Eigen::VectorXd Unbounded(int n, double sign) {
  return Eigen::VectorXd::Constant(n, sign * kInfinity);
}

}  // namespace testing
}  // namespace vesselid

#include "engine/design/design_criterion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "Eigen/Eigenvalues"

namespace vesselid {

double CriterionValue(const Eigen::MatrixXd& m, DesignCriterion criterion, int parameter) {
  const int n = static_cast<int>(m.rows());
  if (n == 0) return 0.0;
  const double eps = 1e-9 * std::max(m.diagonal().maxCoeff(), 1e-300);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(m);
  const Eigen::VectorXd lambda = solver.eigenvalues().cwiseMax(0.0).array() + eps;
  switch (criterion) {
    case DesignCriterion::kD:
      return -lambda.array().log().sum();
    case DesignCriterion::kA:
      return lambda.cwiseInverse().sum();
    case DesignCriterion::kE:
      return -solver.eigenvalues().minCoeff();
    case DesignCriterion::kParameter: {
      const Eigen::VectorXd v = solver.eigenvectors().row(parameter).transpose();
      return (v.array().square() / lambda.array()).sum();
    }
  }
  return 0.0;
}

std::vector<double> PredictedStdErrors(const Eigen::MatrixXd& information,
                                       const std::vector<double>& scale) {
  const int n = static_cast<int>(information.rows());
  const Eigen::VectorXd s = Eigen::Map<const Eigen::VectorXd>(scale.data(), n);
  const Eigen::MatrixXd relative = s.asDiagonal() * information * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(relative);
  const Eigen::VectorXd& lambda = solver.eigenvalues();
  const double largest = n > 0 ? lambda.maxCoeff() : 0.0;
  std::vector<double> se(n, std::numeric_limits<double>::infinity());
  if (!(largest > 0.0)) return se;
  for (int i = 0; i < n; ++i) {
    double variance = 0.0, lost = 0.0;
    for (int k = 0; k < n; ++k) {
      const double v2 = solver.eigenvectors()(i, k) * solver.eigenvectors()(i, k);
      if (lambda[k] > 1e-12 * largest) {
        variance += v2 / lambda[k];
      } else {
        lost += v2;
      }
    }
    if (lost < 1e-6) se[i] = std::sqrt(variance) * s[i];
  }
  return se;
}

Eigen::MatrixXd InformationOfCovariance(const Eigen::MatrixXd& covariance) {
  const int n = static_cast<int>(covariance.rows());
  if (n == 0) return covariance;
  const Eigen::VectorXd d = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  Eigen::VectorXd inv_d(n);
  for (int i = 0; i < n; ++i) inv_d[i] = d[i] > 0.0 ? 1.0 / d[i] : 0.0;
  // On the correlation, so that the rank decision does not depend on the units.
  const Eigen::MatrixXd r = inv_d.asDiagonal() * covariance * inv_d.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(r);
  const Eigen::VectorXd& lambda = solver.eigenvalues();
  const double largest = lambda.maxCoeff();
  Eigen::MatrixXd inverse = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    if (!(lambda[k] > 1e-12 * largest)) continue;
    inverse += solver.eigenvectors().col(k) * solver.eigenvectors().col(k).transpose() / lambda[k];
  }
  return inv_d.asDiagonal() * inverse * inv_d.asDiagonal();
}

}  // namespace vesselid

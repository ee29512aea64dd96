#include "engine/data/savitzky_golay.h"

#include <algorithm>
#include <cmath>

#include "Eigen/Dense"

namespace vesselid {

bool SavitzkyGolay(const std::vector<double>& y, double dt, const SavitzkyGolayOptions& options,
                   std::vector<double>* out, std::string* error) {
  const int m = options.half_width, order = options.order, d = options.derivative;
  const int width = 2 * m + 1, n = static_cast<int>(y.size());
  if (m < 1 || order < 0 || order >= width) {
    *error = "Savitzky-Golay needs half_width >= 1 and 0 <= order < 2 half_width + 1";
    return false;
  }
  if (d < 0 || d > order) {
    *error = "Savitzky-Golay derivative must be between 0 and the order";
    return false;
  }
  if (n < width) {
    *error = "Savitzky-Golay window of " + std::to_string(width) + " samples is longer than the " +
             std::to_string(n) + " samples given";
    return false;
  }
  if (!(dt > 0.0)) {
    *error = "Savitzky-Golay sample interval must be > 0";
    return false;
  }
  // Polynomial coefficients from the window: c = (A^T A)^-1 A^T y, A(k, j) = (k - m)^j.
  Eigen::MatrixXd a(width, order + 1);
  for (int k = 0; k < width; ++k) {
    for (int j = 0; j <= order; ++j) a(k, j) = std::pow(static_cast<double>(k - m), j);
  }
  const Eigen::MatrixXd fit = (a.transpose() * a).ldlt().solve(a.transpose());
  // Weights for the d-th derivative at offset s in [-m, m]: row of d^d/ds^d s^j, times fit.
  std::vector<Eigen::RowVectorXd> weights(width);
  for (int s = -m; s <= m; ++s) {
    Eigen::RowVectorXd basis = Eigen::RowVectorXd::Zero(order + 1);
    for (int j = d; j <= order; ++j) {
      double falling = 1.0;  // j! / (j - d)!
      for (int q = 0; q < d; ++q) falling *= j - q;
      basis[j] = falling * std::pow(static_cast<double>(s), j - d);
    }
    weights[s + m] = basis * fit / std::pow(dt, d);
  }
  out->assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const int first = std::clamp(i - m, 0, n - width);
    const Eigen::RowVectorXd& w = weights[i - first];
    double sum = 0.0;
    for (int k = 0; k < width; ++k) sum += w[k] * y[first + k];
    (*out)[i] = sum;
  }
  return true;
}

}  // namespace vesselid

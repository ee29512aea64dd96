// Quantiles of Student's t distribution with nu degrees of freedom, for prediction intervals
// from a handful of runs: the CDF F(t) = 1/2 + integral_0^t f, f(s) = Gamma((nu+1)/2) /
// (sqrt(nu pi) Gamma(nu/2)) (1 + s^2/nu)^(-(nu+1)/2), by composite Simpson (2000 panels:
// 1e-9 for nu >= 1 up to |t| = 100), inverted by bisection.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesselid {

inline double StudentTCdf(double t, double nu) {
  if (!(nu > 0.0) || std::isnan(t)) return std::numeric_limits<double>::quiet_NaN();
  const double log_norm = std::lgamma(0.5 * (nu + 1.0)) - std::lgamma(0.5 * nu) -
                          0.5 * std::log(nu * 3.14159265358979323846);
  auto density = [&](double s) {
    return std::exp(log_norm - 0.5 * (nu + 1.0) * std::log1p(s * s / nu));
  };
  const double a = std::min(std::abs(t), 1e3);
  constexpr int kPanels = 2000;
  const double h = a / kPanels;
  double sum = density(0.0) + density(a);
  for (int k = 1; k < kPanels; ++k) sum += (k % 2 ? 4.0 : 2.0) * density(k * h);
  const double half = sum * h / 3.0;
  return t >= 0.0 ? 0.5 + half : 0.5 - half;
}

// The p-quantile (0 < p < 1); NaN outside.
inline double StudentTQuantile(double p, double nu) {
  if (!(p > 0.0 && p < 1.0) || !(nu > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  double low = -1e3, high = 1e3;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (low + high);
    (StudentTCdf(mid, nu) < p ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

}  // namespace vesselid

// Small statistics the studies need: normal and chi-square(1) quantiles, mean and SD.
#pragma once

#include <cmath>
#include <vector>

namespace vesselid {

// Standard normal quantile: z with Phi(z) = p, 0 < p < 1 (bisection on erfc to 1e-12).
inline double NormalQuantile(double p) {
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Two-sided interval half-width in standard deviations for `confidence` (1.96 for 0.95).
inline double TwoSidedZ(double confidence) { return NormalQuantile(0.5 * (1.0 + confidence)); }

// chi2 quantile with one degree of freedom: z^2 of the two-sided normal interval (3.84).
inline double ChiSquare1Quantile(double confidence) {
  const double z = TwoSidedZ(confidence);
  return z * z;
}

struct MeanSd {
  int n = 0;
  double mean = NAN, sd = NAN;
};

// Mean and sample standard deviation of the finite values.
inline MeanSd Summarise(const std::vector<double>& values) {
  MeanSd s;
  double sum = 0.0;
  for (double v : values) {
    if (std::isfinite(v)) {
      sum += v;
      ++s.n;
    }
  }
  if (s.n == 0) return s;
  s.mean = sum / s.n;
  double ss = 0.0;
  for (double v : values) {
    if (std::isfinite(v)) ss += (v - s.mean) * (v - s.mean);
  }
  s.sd = s.n > 1 ? std::sqrt(ss / (s.n - 1)) : NAN;
  return s;
}

}  // namespace vesselid

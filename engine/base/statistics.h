// Small statistics: normal and chi-square(1) quantiles, mean and SD, medians.
#pragma once

#include <algorithm>
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

// The median of values already in ascending order (the mean of the middle two for an even
// count); `if_empty` for none.
inline double SortedMedian(const std::vector<double>& values, double if_empty = NAN) {
  const size_t n = values.size();
  if (n == 0) return if_empty;
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// The median (the mean of the middle two for an even count); `if_empty` for none.
inline double Median(std::vector<double> values, double if_empty = NAN) {
  std::sort(values.begin(), values.end());
  return SortedMedian(values, if_empty);
}

// The upper median: the element at n/2 of the sorted values, always one of them; `if_empty`
// for none.
inline double UpperMedian(std::vector<double> values, double if_empty = NAN) {
  if (values.empty()) return if_empty;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace vesselid

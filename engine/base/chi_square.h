// Upper tail of the chi-square distribution through the regularised upper incomplete gamma
// function
//   Q(a, x) = Gamma(a, x) / Gamma(a) = 1/Gamma(a) int_x^inf t^(a-1) e^-t dt,
//   P(chi2_k > q) = Q(k/2, q/2),
// evaluated by the power series of P = 1 - Q for x < a + 1 and by the continued fraction of
// Q (modified Lentz) otherwise, each to double precision; the prefactor e^-x x^a / Gamma(a)
// in logarithms, so that Q underflows to 0 only where it is below ~1e-308.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesselid {

// Q(a, x) for a > 0, x >= 0; NaN otherwise.
inline double RegularizedUpperGamma(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0) || !std::isfinite(a)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (x == 0.0) return 1.0;
  if (std::isinf(x)) return 0.0;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  constexpr double kEpsilon = 1e-16;
  constexpr int kMaxTerms = 100000;
  if (x < a + 1.0) {
    // P(a, x) = e^-x x^a / Gamma(a + 1) sum_n x^n / ((a + 1) ... (a + n)).
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < kMaxTerms; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * kEpsilon) break;
    }
    return std::max(0.0, 1.0 - sum * std::exp(log_prefactor));
  }
  // Q(a, x) = e^-x x^a / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - ...)).
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int n = 1; n < kMaxTerms; ++n) {
    const double an = -n * (n - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < kEpsilon) break;
  }
  return std::exp(log_prefactor) * h;
}

// P(chi2 with `dof` degrees of freedom > q).
inline double ChiSquareUpperTail(double q, double dof) {
  return RegularizedUpperGamma(0.5 * dof, 0.5 * std::max(q, 0.0));
}

}  // namespace vesselid

#include "engine/data/interpolation.h"

#include <algorithm>

#include "engine/base/check.h"

namespace vesselid {

const char* InterpolationToString(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::kZeroOrderHold:
      return "zero_order_hold";
    case Interpolation::kLinear:
      return "linear";
    case Interpolation::kCubic:
      return "cubic";
  }
  return "unknown";
}

bool StringToInterpolation(const std::string& text, Interpolation* interpolation) {
  for (Interpolation candidate :
       {Interpolation::kZeroOrderHold, Interpolation::kLinear, Interpolation::kCubic}) {
    if (text == InterpolationToString(candidate)) {
      *interpolation = candidate;
      return true;
    }
  }
  return false;
}

namespace {

// Catmull-Rom slope at sample k (one-sided at the ends).
double Slope(const Channel& c, size_t k) {
  const size_t n = c.t.size();
  size_t lo = k == 0 ? 0 : k - 1;
  size_t hi = k + 1 == n ? k : k + 1;
  return (c.value[hi] - c.value[lo]) / (c.t[hi] - c.t[lo]);
}

}  // namespace

std::vector<double> InterpolateAt(const Channel& c, Interpolation interpolation,
                                  const std::vector<double>& times, bool left_limit) {
  VESSELID_CHECK(!c.t.empty());
  std::vector<double> out(times.size());
  const size_t n = c.t.size();
  // c.t[k] <= t < c.t[k+1] (c.t[k] < t <= c.t[k+1] for the left limit), k walking forward
  // over the increasing times from where the first one lies (bisection, not a walk from the
  // channel's start: a segment's times lie in a short stretch of a long record).
  size_t k = 0;
  if (!times.empty()) {
    const double t = times.front();
    const auto after = left_limit ? std::lower_bound(c.t.begin(), c.t.end(), t)
                                  : std::upper_bound(c.t.begin(), c.t.end(), t);
    k = after == c.t.begin() ? 0 : static_cast<size_t>(after - c.t.begin()) - 1;
  }
  for (size_t i = 0; i < times.size(); ++i) {
    const double t = times[i];
    while (k + 1 < n && (left_limit ? c.t[k + 1] < t : c.t[k + 1] <= t)) ++k;
    if (t <= c.t[0]) {
      out[i] = c.value[0];
      continue;
    }
    if (k + 1 == n) {
      out[i] = c.value[n - 1];
      continue;
    }
    const double h = c.t[k + 1] - c.t[k];
    const double s = (t - c.t[k]) / h;
    switch (interpolation) {
      case Interpolation::kZeroOrderHold:
        out[i] = c.value[k];
        break;
      case Interpolation::kLinear:
        out[i] = c.value[k] + s * (c.value[k + 1] - c.value[k]);
        break;
      case Interpolation::kCubic: {
        const double s2 = s * s, s3 = s2 * s;
        out[i] = (2 * s3 - 3 * s2 + 1) * c.value[k] + (s3 - 2 * s2 + s) * h * Slope(c, k) +
                 (-2 * s3 + 3 * s2) * c.value[k + 1] + (s3 - s2) * h * Slope(c, k + 1);
        break;
      }
    }
  }
  return out;
}

}  // namespace vesselid

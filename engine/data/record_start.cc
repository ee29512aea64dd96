#include "engine/data/record_start.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "Eigen/Dense"
#include "engine/base/angle.h"

namespace vesselid {

bool FitStart(const Channel& channel, double t0, double window, bool angle, StartFit* fit) {
  constexpr double kTimeTolerance = 1e-9;
  std::vector<double> dt, y;
  // The first sample not before t0 - tolerance, by bisection with the scan's own test.
  const size_t begin = std::partition_point(channel.t.begin(), channel.t.end(),
                                            [&](double t) { return t - t0 < -kTimeTolerance; }) -
                       channel.t.begin();
  for (size_t i = begin; i < channel.t.size(); ++i) {
    const double tau = channel.t[i] - t0;
    if (tau < -kTimeTolerance) continue;
    if (tau > window && dt.size() >= 3) break;
    double v = channel.value[i];
    if (angle && !y.empty()) v = y.back() + WrapAngle(v - y.back());
    dt.push_back(tau);
    y.push_back(v);
  }
  if (dt.size() < 3) return false;
  // Normal equations of the quadratic in tau / span (well conditioned on any time scale).
  const double span = dt.back() > 0.0 ? dt.back() : 1.0;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < dt.size(); ++i) {
    const double s = dt[i] / span;
    const Eigen::Vector3d row(1.0, s, s * s);
    normal += row * row.transpose();
    rhs += row * y[i];
  }
  const Eigen::Vector3d c = normal.ldlt().solve(rhs);
  if (!c.allFinite()) return false;
  double ssr = 0.0;
  for (size_t i = 0; i < dt.size(); ++i) {
    const double s = dt[i] / span;
    const double e = y[i] - (c[0] + c[1] * s + c[2] * s * s);
    ssr += e * e;
  }
  const int dof = static_cast<int>(dt.size()) - 3;
  const Eigen::Matrix3d inverse = normal.inverse();
  const double s2 = dof > 0 ? ssr / dof : std::nan("");
  fit->value = c[0];
  fit->rate = c[1] / span;
  fit->value_sigma = std::sqrt(s2 * inverse(0, 0));
  fit->rate_sigma = std::sqrt(s2 * inverse(1, 1)) / span;
  return true;
}

bool RateAt(const Channel& channel, double t0, double window, bool angle, double* rate) {
  StartFit fit;
  if (!FitStart(channel, t0, window, angle, &fit)) return false;
  *rate = fit.rate;
  return true;
}

}  // namespace vesselid

#include "engine/data/record_start.h"

#include <cmath>
#include <vector>

#include "Eigen/Dense"
#include "engine/base/angle.h"

namespace vesselid {

bool RateAt(const Channel& channel, double t0, double window, bool angle, double* rate) {
  constexpr double kTimeTolerance = 1e-9;
  std::vector<double> dt, y;
  for (size_t i = 0; i < channel.t.size(); ++i) {
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
  *rate = c[1] / span;
  return true;
}

}  // namespace vesselid

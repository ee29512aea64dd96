#include "problems/input_gain/quadratic_usv.h"

#include <cmath>

#include "problems/input_gain/all_finite.h"

namespace vesselid::input_gain {
namespace {

constexpr int kStrips = 16;  // cross-flow strips along the hull

}  // namespace

double QuadraticThrust(const QuadraticUsvParameters& p, double w) {
  return (w >= 0.0 ? p.thrust_ahead : p.thrust_astern) * w * std::abs(w);
}

bool QuadraticUsvDerivative(const QuadraticUsvParameters& p, const double* x, const double* pwm,
                            double* xdot) {
  if (!AllFinite(x, kQuadraticUsvStates) || !AllFinite(pwm, 2)) return false;
  const double psi = x[kPsi], u = x[kU], v = x[kV], r = x[kR];
  const double c = std::cos(psi), s = std::sin(psi);
  xdot[kN] = u * c - v * s;
  xdot[kE] = u * s + v * c;
  xdot[kPsi] = r;

  // Cross-flow drag, midpoint rule over the hull from -L/2 to L/2.
  double y_cf = 0.0, n_cf = 0.0;
  const double dx = p.hull_length / kStrips;
  for (int j = 0; j < kStrips; ++j) {
    const double xj = -0.5 * p.hull_length + (j + 0.5) * dx;
    const double flow = v + xj * r;
    y_cf -= p.cross_flow * std::abs(flow) * flow * dx;
    n_cf -= p.cross_flow * xj * std::abs(flow) * flow * dx;
  }
  // C_RB nu + C_A nu (CG at the origin), rows u, v, r.
  const double cu = -p.m * v * r + (p.Yvdot * v + p.Yrdot * r) * r;
  const double cv = p.m * u * r - p.Xudot * u * r;
  const double cr =
      -(p.Yvdot * v + p.Yrdot * r) * u + p.Xudot * u * v;  // Munk: (Xudot - Yvdot) u v
  const double du = -p.Xu * u - p.Xuu * std::abs(u) * u;
  const double dv = -p.Yv * v - p.Yr * r;
  const double dr = -p.Nv * v - p.Nr * r;
  const double thrust_l = QuadraticThrust(p, x[kWL]), thrust_r = QuadraticThrust(p, x[kWR]);
  const double fu = thrust_l + thrust_r - cu - du;
  const double fv = y_cf - cv - dv;
  const double fr = p.lever * (thrust_l - thrust_r) + n_cf - cr - dr;

  const double m11 = p.m - p.Xudot;
  const double m22 = p.m - p.Yvdot, m23 = -p.Yrdot;
  const double m32 = -p.Nvdot, m33 = p.Iz - p.Nrdot;
  const double det = m22 * m33 - m23 * m32;
  xdot[kU] = fu / m11;
  xdot[kV] = (m33 * fv - m23 * fr) / det;
  xdot[kR] = (m22 * fr - m32 * fv) / det;
  xdot[kWL] = (pwm[0] - x[kWL]) / p.propeller_lag;
  xdot[kWR] = (pwm[1] - x[kWR]) / p.propeller_lag;
  return AllFinite(xdot, kQuadraticUsvStates);
}

}  // namespace vesselid::input_gain

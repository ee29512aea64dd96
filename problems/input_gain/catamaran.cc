#include "problems/input_gain/catamaran.h"

#include <cmath>

#include "problems/input_gain/all_finite.h"

namespace vesselid::input_gain {

double StaticThrust(const CatamaranParameters& p, double pwm) {
  const double a = p.linear_share;
  if (pwm > p.dead_forward) {
    const double s = (pwm - p.dead_forward) / (1.0 - p.dead_forward);
    return p.thrust_forward * (a * s + (1.0 - a) * s * s);
  }
  if (pwm < p.dead_reverse) {
    const double s = (pwm - p.dead_reverse) / (-1.0 - p.dead_reverse);
    return -p.thrust_reverse * (a * s + (1.0 - a) * s * s);
  }
  return 0.0;
}

double EffectiveThrust(const CatamaranParameters& p, double pwm, double u) {
  const double t0 = StaticThrust(p, pwm);
  return t0 > 0.0 ? t0 * (1.0 - p.thrust_deduction * u) : t0;
}

bool CatamaranDerivative(const CatamaranParameters& p, const double* x, const double* pwm,
                         double* xdot) {
  if (!AllFinite(x, kCatamaranStates) || !AllFinite(pwm, 2)) return false;
  const double psi = x[kPsi], u = x[kU], v = x[kV], r = x[kR];
  const double c = std::cos(psi), s = std::sin(psi);
  xdot[kN] = u * c - v * s;
  xdot[kE] = u * s + v * c;
  xdot[kPsi] = r;

  // Right-hand side tau + tau_wind - C nu - D nu, row by row.
  const double vg = p.xg * r + v;  // m (xg r + v) is the C_RB (1,3) entry over m
  const double cu = -p.m * vg * r + (p.Yvdot * v + p.Yrdot * r) * r;
  const double cv = p.m * u * r - p.Xudot * u * r;
  const double cr = p.m * vg * u - p.m * u * v - (p.Yvdot * v + p.Yrdot * r) * u + p.Xudot * u * v;
  const double du = -p.Xu * u - p.Xuu * std::abs(u) * u;
  const double dv = -p.Yv * v - p.Yr * r - p.Yvv * std::abs(v) * v;
  const double dr = -p.Nv * v - p.Nr * r - p.Nrr * std::abs(r) * r - p.Nuv * u * v;
  const double wind_x = p.wind_north * c + p.wind_east * s;  // R(psi)^T [F_n, F_e]
  const double wind_y = -p.wind_north * s + p.wind_east * c;
  const double fu = x[kTL] + x[kTR] + wind_x - cu - du;
  const double fv = wind_y - cv - dv;
  const double fr = p.lever * (x[kTL] - x[kTR]) - cr - dr;

  // M is block diagonal: surge alone, sway-yaw 2x2.
  const double m11 = p.m - p.Xudot;
  const double m22 = p.m - p.Yvdot, m23 = p.m * p.xg - p.Yrdot;
  const double m32 = p.m * p.xg - p.Nvdot, m33 = p.Iz - p.Nrdot;
  const double det = m22 * m33 - m23 * m32;
  if (m11 == 0.0 || det == 0.0) return false;
  xdot[kU] = fu / m11;
  xdot[kV] = (m33 * fv - m23 * fr) / det;
  xdot[kR] = (m22 * fr - m32 * fv) / det;

  xdot[kTL] = (EffectiveThrust(p, pwm[0], u) - x[kTL]) / p.motor_time_constant;
  xdot[kTR] = (EffectiveThrust(p, pwm[1], u) - x[kTR]) / p.motor_time_constant;
  return AllFinite(xdot, kCatamaranStates);
}

}  // namespace vesselid::input_gain

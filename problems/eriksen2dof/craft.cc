#include "problems/eriksen2dof/craft.h"

#include <algorithm>
#include <cmath>

#include "engine/model/rk4.h"

namespace vesselid::eriksen2dof {
namespace {

bool AllFinite(const double* x, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) return false;
  }
  return true;
}

// Ground velocity [N', E'] of state x.
void GroundVelocity(const double* x, const CraftEnvironment& env, double* n_dot, double* e_dot) {
  const double c = std::cos(x[kCraftPsi]), s = std::sin(x[kCraftPsi]);
  *n_dot = x[kCraftU] * c - x[kCraftV] * s + env.current_n;
  *e_dot = x[kCraftU] * s + x[kCraftV] * c + env.current_e;
}

// Straight-run speed where T_c(tau_m) = R(u) + k_x u^2, by bisection.
double BalanceSpeed(const CraftParameters& p, double tau_m) {
  const double thrust = CommandedThrust(p, tau_m);
  double lo = 0.0, hi = 100.0;
  for (int i = 0; i < 200; ++i) {
    const double u = 0.5 * (lo + hi);
    (HullResistance(p, u) + p.air_drag_x * u * u < thrust ? lo : hi) = u;
  }
  return lo;
}

// Solves the 3x3 system a z = b by Cramer's rule; false when a is singular.
bool Solve3(const double a[3][3], const double* b, double* z) {
  auto det3 = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det3(a);
  if (!(std::abs(d) > 0.0) || !std::isfinite(d)) return false;
  for (int j = 0; j < 3; ++j) {
    double m[3][3];
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) m[i][k] = k == j ? b[i] : a[i][k];
    }
    z[j] = det3(m) / d;
  }
  return true;
}

}  // namespace

double ThrottleCurve(const CraftParameters& p, double tau_m) {
  const double t = std::clamp(tau_m, 0.0, 1.0), knee = p.throttle_knee;
  // Slope s below the knee, s / ratio above: s knee + s (1 - knee) / ratio = 1.
  const double slope = 1.0 / (knee + (1.0 - knee) / p.knee_slope_ratio);
  return t <= knee ? slope * t : slope * knee + slope / p.knee_slope_ratio * (t - knee);
}

double CommandedThrust(const CraftParameters& p, double tau_m) {
  return p.thrust_idle + (p.thrust_max - p.thrust_idle) * ThrottleCurve(p, tau_m);
}

double HullResistance(const CraftParameters& p, double u) {
  const double a = std::abs(u);
  const double hump = p.hump_force * (std::tanh((a - p.hump_speed) / p.hump_width) +
                                      std::tanh(p.hump_speed / p.hump_width));
  return (u < 0.0 ? -hump : hump) + p.drag_linear * u + p.drag_quadratic * a * u;
}

double SurgeTimeConstant(const CraftParameters& p, double u) {
  const double a = std::abs(u);
  const double sech = 1.0 / std::cosh((a - p.hump_speed) / p.hump_width);
  const double slope = p.hump_force / p.hump_width * sech * sech + p.drag_linear +
                       2.0 * p.drag_quadratic * a + 2.0 * p.air_drag_x * a;
  return p.m_u / slope;
}

bool CraftDerivative(const CraftParameters& p, const double* x, const double* tau,
                     const CraftEnvironment& env, double* xdot) {
  if (!AllFinite(x, kCraftStates) || !AllFinite(tau, 2)) return false;
  const double psi = x[kCraftPsi], u = x[kCraftU], v = x[kCraftV], r = x[kCraftR];
  const double thrust = x[kCraftThrust], angle = x[kCraftAngle];
  const double c = std::cos(psi), s = std::sin(psi);
  GroundVelocity(x, env, &xdot[kCraftN], &xdot[kCraftE]);
  xdot[kCraftPsi] = r;

  // Apparent wind in body axes and its force and moment.
  const double air_n = env.wind_n - xdot[kCraftN], air_e = env.wind_e - xdot[kCraftE];
  const double air_x = c * air_n + s * air_e, air_y = -s * air_n + c * air_e;
  const double air = std::hypot(air_x, air_y);
  const double wind_x = p.air_drag_x * air * air_x, wind_y = p.air_drag_y * air * air_y;

  const double side = thrust * std::sin(angle);
  const double fu = thrust * std::cos(angle) - HullResistance(p, u) + p.m_v * v * r -
                    p.turn_drag * p.m * u * r * r + wind_x;
  const double fv = -p.m_u * u * r - (p.sway_damping + p.sway_damping_speed * std::abs(u)) * v -
                    p.sway_damping_quadratic * std::abs(v) * v - side + wind_y;
  const double fr = p.thrust_lever * side -
                    (p.yaw_damping + p.yaw_damping_speed * std::abs(u)) * r -
                    p.yaw_damping_cubic * r * r * r + p.wind_lever * wind_y;
  xdot[kCraftU] = fu / p.m_u;
  xdot[kCraftV] = fv / p.m_v;
  xdot[kCraftR] = fr / p.I_r;

  const double tau_m = std::clamp(tau[0], 0.0, 1.0), tau_delta = std::clamp(tau[1], -1.0, 1.0);
  xdot[kCraftThrust] = (CommandedThrust(p, tau_m) - thrust) / p.motor_time_constant;
  xdot[kCraftAngle] = (p.rudder_max * tau_delta - angle) / p.rudder_time_constant;
  return AllFinite(xdot, kCraftStates);
}

void GroundTrack(const double* x, const CraftEnvironment& environment, double* sog,
                 double* course) {
  double n_dot = 0.0, e_dot = 0.0;
  GroundVelocity(x, environment, &n_dot, &e_dot);
  *sog = std::hypot(n_dot, e_dot);
  *course = std::atan2(e_dot, n_dot);
}

bool SteadyState(const CraftParameters& p, double tau_m, double tau_delta,
                 CraftSteadyState* steady) {
  const CraftEnvironment calm;
  const CraftRhs rhs{&p, &calm};
  const double tau[2] = {std::clamp(tau_m, 0.0, 1.0), std::clamp(tau_delta, -1.0, 1.0)};
  double x[kCraftStates] = {};
  x[kCraftU] = BalanceSpeed(p, tau[0]);
  x[kCraftThrust] = CommandedThrust(p, tau[0]);
  x[kCraftAngle] = p.rudder_max * tau[1];

  // Integrate until the velocities stop changing (the slowest mode, surge at idle, has a
  // time constant of ~20 s).
  const double h = 0.05;
  double xdot[kCraftStates];
  for (int k = 0; k < 40000; ++k) {
    if (!Rk4Step<CraftRhs, double>(rhs, tau, tau, tau, nullptr, h, x)) return false;
    if (k % 100 == 0) {
      if (!CraftDerivative(p, x, tau, calm, xdot)) return false;
      if (std::abs(xdot[kCraftU]) < 1e-9 && std::abs(xdot[kCraftV]) < 1e-9 &&
          std::abs(xdot[kCraftR]) < 1e-10) {
        break;
      }
    }
  }

  // Newton polish on (u, v, r) with T and delta at their commanded values.
  const int index[3] = {kCraftU, kCraftV, kCraftR};
  for (int iteration = 0; iteration < 8; ++iteration) {
    if (!CraftDerivative(p, x, tau, calm, xdot)) return false;
    double f[3], jacobian[3][3];
    for (int i = 0; i < 3; ++i) f[i] = xdot[index[i]];
    for (int j = 0; j < 3; ++j) {
      double xp[kCraftStates], fp[kCraftStates];
      std::copy(x, x + kCraftStates, xp);
      const double d = 1e-7 * std::max(1.0, std::abs(x[index[j]]));
      xp[index[j]] += d;
      if (!CraftDerivative(p, xp, tau, calm, fp)) return false;
      for (int i = 0; i < 3; ++i) jacobian[i][j] = (fp[index[i]] - f[i]) / d;
    }
    double step[3];
    if (!Solve3(jacobian, f, step)) return false;
    for (int j = 0; j < 3; ++j) x[index[j]] -= step[j];
  }
  if (!CraftDerivative(p, x, tau, calm, xdot)) return false;
  if (std::abs(xdot[kCraftU]) > 1e-8 || std::abs(xdot[kCraftV]) > 1e-8 ||
      std::abs(xdot[kCraftR]) > 1e-9) {
    return false;
  }
  steady->u = x[kCraftU];
  steady->v = x[kCraftV];
  steady->r = x[kCraftR];
  steady->thrust = x[kCraftThrust];
  steady->angle = x[kCraftAngle];
  steady->sog = std::hypot(x[kCraftU], x[kCraftV]);
  return true;
}

}  // namespace vesselid::eriksen2dof

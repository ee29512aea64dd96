// Erunsal 6-DOF vessel (seed 002) in Fossen form, as restated in MODELS.md §1:
//
//   eta' = J(eta) nu,   M nu' + C(nu) nu + D(nu) nu + g(eta) = tau_thr + tau_air
//
// eta = [x y z phi theta psi] (NED), nu = [u v w p q r] (body), origin at the CG.
//   M      = M_RB + M_A: diag(m - Xudot, m - Yvdot, m - Zwdot, Ix - Kpdot, Iy - Mqdot, Iz - Nrdot)
//            with M(roll, yaw) = -Ixz and M(sway, yaw) = -Yrdot (symmetric)
//   C nu   = [w x h1; w x h2 + v1 x h1],  [h1; h2] = M nu  (Kirchhoff form)
//   D nu   = -[Xu u + Xuu|u|u; Yv v + Yr r + Yvv|v|v; Zw w + Zww|w|w;
//              Kp p + Kpp|p|p; Mq q + Mqq|q|q; Nv v + Nr r + Nrr|r|r]
//   g      = [0, 0, k_z z, k_phi sin phi, k_theta sin theta, 0]
//   tau_air = -1/2 rho_air C_DA [A_x |u_rw| u_rw, A_y |v_rw| v_rw, 0, 0, 0, 0]
//   tau_thr = [F_L + F_R, 0, 0, 0, 0, l_y (F_L - F_R)],  F_L = L_TS c_L + L_TO, F_R = R_TS c_R + R_TO
//
// DOF restriction: with active set A, inactive velocities and positions are held at zero and
// M[A,A] nu'[A] = (tau - C nu - D nu - g)[A]. Inputs: thruster commands c_L, c_R (absent:
// motors off, tau_thr = 0) and wind speed and the direction it blows towards (absent: still
// air). Outputs: the 12 states and the thrusts F_L, F_R.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "engine/model/model.h"

namespace vesselid::erunsal6dof {

enum Dof { kSurge, kSway, kHeave, kRoll, kPitch, kYaw };
const char* DofToString(int dof);
bool StringToDof(const std::string& text, int* dof);

// Parameter order of the model (MODELS.md's list).
enum Parameter {
  kIx, kIy, kIz, kIxz,
  kXudot, kYvdot, kYrdot, kNrdot, kZwdot, kKpdot, kMqdot,
  kXu, kYv, kZw, kKp, kMq, kNr, kYr, kNv,
  kXuu, kYvv, kZww, kKpp, kMqq, kNrr,
  kCDA,
  kLTS, kLTO, kRTS, kRTO,
  kNumParameters
};

// Known constants; defaults are the reference tugboat of MODELS.md.
struct Constants {
  double m = 11.0;
  double l_y = 0.06;
  double A_x = 0.05;
  double A_y = 0.18;
  double k_z = 1837.0;
  double k_phi = 4.32;
  double k_theta = 97.1;
  double rho_air = 1.225;
};

// Reference-vessel parameter values (MODELS.md table), in Parameter order.
std::vector<double> ReferenceParameters();
std::vector<std::string> ParameterNames();

struct Model {
  static constexpr int kNumStates = 12;
  static constexpr int kNumInputs = 4;   // c_L, c_R, wind_speed, wind_direction
  static constexpr int kNumOutputs = 14;  // 12 states, F_L, F_R

  Constants constants;
  std::array<bool, 6> active = {true, true, true, true, true, true};

  ModelInfo Info() const;

  // Physical admissibility of a parameter vector: M symmetric positive definite, symmetric
  // part of the linear damping positive semi-definite. Empty when admissible.
  std::vector<std::string> Admissibility(const double* p, const double* state_limits) const;

  // Start values of unmeasured body velocities from the measured position and Euler-angle
  // rates: [u v w] = R(phi, theta, psi)^T [x' y' z'], [p q r] = T(phi, theta)^-1 [phi' theta'
  // psi']; an unmeasured rate counts as zero, inactive DOFs stay zero.
  void GuessState(const double* y, const double* ydot, double* x) const;

  template <class T, class U>
  bool operator()(const T* x, const U* u, const T* p, T* xdot) const;

  template <class T, class U>
  void Output(const T* x, const U* u, const T* p, T* y) const {
    for (int i = 0; i < kNumStates; ++i) y[i] = x[i];
    Thrust(u, p, &y[12], &y[13]);
  }

 private:
  template <class T, class U>
  static void Thrust(const U* u, const T* p, T* left, T* right) {
    using std::isnan;
    *left = isnan(u[0]) ? T(0.0) : p[kLTS] * u[0] + p[kLTO];
    *right = isnan(u[1]) ? T(0.0) : p[kRTS] * u[1] + p[kRTO];
  }
};

template <class T, class U>
bool Model::operator()(const T* x, const U* u, const T* p, T* xdot) const {
  using std::abs;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Constants& c = constants;
  // Restricted state: inactive positions and velocities are zero.
  std::array<T, 6> eta, nu;
  for (int i = 0; i < 6; ++i) {
    eta[i] = active[i] ? x[i] : T(0.0);
    nu[i] = active[i] ? x[6 + i] : T(0.0);
  }
  const T &uu = nu[0], &v = nu[1], &w = nu[2], &pr = nu[3], &q = nu[4], &r = nu[5];
  const T &phi = eta[3], &theta = eta[4], &psi = eta[5];

  // Mass matrix: diagonal d plus the symmetric couplings M(sway, yaw) = -Yrdot and
  // M(roll, yaw) = -Ixz. Only what the active set uses is formed (the hot path runs on Jets,
  // where even a product with a zero costs the full width).
  const T zero(0.0);
  T d[6];
  const Parameter added[6] = {kXudot, kYvdot, kZwdot, kKpdot, kMqdot, kNrdot};
  const Parameter inertia[3] = {kIx, kIy, kIz};
  for (int i = 0; i < 6; ++i) {
    if (active[i]) d[i] = (i < 3 ? T(c.m) : p[inertia[i - 3]]) - p[added[i]];
  }
  const bool sway_yaw = active[1] && active[5], roll_yaw = active[3] && active[5];
  const T m15 = sway_yaw ? -p[kYrdot] : zero, m35 = roll_yaw ? -p[kIxz] : zero;
  auto entry = [&](int i, int j) -> const T& {
    if (i == j) return d[i];
    if ((i == 1 && j == 5) || (i == 5 && j == 1)) return m15;
    if ((i == 3 && j == 5) || (i == 5 && j == 3)) return m35;
    return zero;
  };

  // Kirchhoff Coriolis: h = M nu, C nu = [w x h1; w x h2 + v1 x h1]; inactive velocities are
  // zero, so only active terms and rows are formed.
  int index[6], k = 0;
  for (int i = 0; i < 6; ++i) {
    if (active[i]) index[k++] = i;
  }
  T h[6];
  for (int i = 0; i < 6; ++i) h[i] = active[i] ? d[i] * nu[i] : zero;
  if (sway_yaw) {
    h[1] += m15 * r;
    h[5] += m15 * v;
  }
  if (roll_yaw) {
    h[3] += m35 * r;
    h[5] += m35 * pr;
  }
  T rhs[6];  // only active rows are used
  for (int i = 0; i < 6; ++i) rhs[i] = T(0.0);
  if (active[0]) rhs[0] = -(q * h[2] - r * h[1]);
  if (active[1]) rhs[1] = -(r * h[0] - pr * h[2]);
  if (active[2]) rhs[2] = -(pr * h[1] - q * h[0]);
  if (active[3]) rhs[3] = -(q * h[5] - r * h[4] + v * h[2] - w * h[1]);
  if (active[4]) rhs[4] = -(r * h[3] - pr * h[5] + w * h[0] - uu * h[2]);
  if (active[5]) rhs[5] = -(pr * h[4] - q * h[3] + uu * h[1] - v * h[0]);

  // Damping (D nu enters with a minus sign: -D nu = +[Xu u + ...]).
  if (active[0]) rhs[0] += p[kXu] * uu + p[kXuu] * abs(uu) * uu;
  if (active[1]) rhs[1] += p[kYv] * v + p[kYr] * r + p[kYvv] * abs(v) * v;
  if (active[2]) rhs[2] += p[kZw] * w + p[kZww] * abs(w) * w;
  if (active[3]) rhs[3] += p[kKp] * pr + p[kKpp] * abs(pr) * pr;
  if (active[4]) rhs[4] += p[kMq] * q + p[kMqq] * abs(q) * q;
  if (active[5]) rhs[5] += p[kNv] * v + p[kNr] * r + p[kNrr] * abs(r) * r;

  // Restoring (inactive angles are zero: no trigonometry on them).
  const T sphi = active[3] ? sin(phi) : T(0.0), cphi = active[3] ? cos(phi) : T(1.0);
  const T sth = active[4] ? sin(theta) : T(0.0), cth = active[4] ? cos(theta) : T(1.0);
  if (active[2]) rhs[2] -= c.k_z * eta[2];
  if (active[3]) rhs[3] -= c.k_phi * sphi;
  if (active[4]) rhs[4] -= c.k_theta * sth;

  // Air drag on the velocity relative to the wind (still air when no wind input).
  T u_rw = uu, v_rw = v;
  using std::isnan;
  if (!isnan(u[2]) && !isnan(u[3]) && u[2] != 0.0) {
    u_rw -= u[2] * cos(u[3] - psi);
    v_rw -= u[2] * sin(u[3] - psi);
  }
  const double half_rho = 0.5 * c.rho_air;
  if (active[0]) rhs[0] -= half_rho * c.A_x * p[kCDA] * abs(u_rw) * u_rw;
  if (active[1]) rhs[1] -= half_rho * c.A_y * p[kCDA] * abs(v_rw) * v_rw;

  // Thrusters.
  if (active[0] || active[5]) {
    T left, right;
    Thrust(u, p, &left, &right);
    rhs[0] += left + right;
    rhs[5] += c.l_y * (left - right);
  }

  // Active accelerations: Cholesky solve of M[A,A] a = rhs[A].
  T L[6][6], a[6];
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j <= i; ++j) {
      T sum = entry(index[i], index[j]);
      for (int l = 0; l < j; ++l) sum -= L[i][l] * L[j][l];
      if (i == j) {
        if (!(sum > 0.0)) return false;  // M[A,A] not positive definite
        L[i][i] = sqrt(sum);
      } else {
        L[i][j] = sum / L[j][j];
      }
    }
  }
  for (int i = 0; i < k; ++i) {  // forward: L y = b
    T sum = rhs[index[i]];
    for (int l = 0; l < i; ++l) sum -= L[i][l] * a[l];
    a[i] = sum / L[i][i];
  }
  for (int i = k - 1; i >= 0; --i) {  // backward: L^T a = y
    T sum = a[i];
    for (int l = i + 1; l < k; ++l) sum -= L[l][i] * a[l];
    a[i] = sum / L[i][i];
  }
  for (int i = 0; i < 6; ++i) xdot[6 + i] = T(0.0);
  for (int i = 0; i < k; ++i) xdot[6 + index[i]] = a[i];

  // Kinematics eta' = J(eta) nu (zyx Euler angles), inactive DOFs held.
  const T cpsi = active[5] ? cos(psi) : T(1.0), spsi = active[5] ? sin(psi) : T(0.0);
  if (!(abs(cth) > 1e-6)) return false;  // Euler singularity
  const T eta_dot[6] = {
      cpsi * cth * uu + (cpsi * sth * sphi - spsi * cphi) * v + (spsi * sphi + cpsi * cphi * sth) * w,
      spsi * cth * uu + (cpsi * cphi + sphi * sth * spsi) * v + (spsi * sth * cphi - cpsi * sphi) * w,
      -sth * uu + cth * sphi * v + cth * cphi * w,
      pr + sphi * sth / cth * q + cphi * sth / cth * r,
      cphi * q - sphi * r,
      sphi / cth * q + cphi / cth * r};
  for (int i = 0; i < 6; ++i) xdot[i] = active[i] ? eta_dot[i] : T(0.0);
  return true;
}

}  // namespace vesselid::erunsal6dof

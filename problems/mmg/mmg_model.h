// The MMG standard 3-DOF manoeuvring model (Yasukawa & Yoshimura 2015, "Introduction of MMG
// standard method for ship maneuvering predictions", J. Mar. Sci. Technol. 20: 37-52;
// docs/models.md restates it). Surge, sway and yaw of a single-screw, single-rudder ship,
// written at midship with the centre of gravity at x_G:
//
//   (m + m_x) u' - (m + m_y) v r - x_G m r^2    = X_H + X_R + X_P
//   (m + m_y) v' + (m + m_x) u r + x_G m r'     = Y_H + Y_R
//   (I_zG + x_G^2 m + J_z) r' + x_G m (v' + u r) = N_H + N_R
//   x0' = u cos psi - v sin psi,  y0' = u sin psi + v cos psi,  psi' = r
//
// Hull:  X_H = 1/2 rho L d U^2 X'_H, Y_H = 1/2 rho L d U^2 Y'_H, N_H = 1/2 rho L^2 d U^2 N'_H,
//   X'_H = -R'_0 + X'_vv v'^2 + X'_vr v' r' + X'_rr r'^2 + X'_vvvv v'^4
//   Y'_H = Y'_v v' + Y'_r r' + Y'_vvv v'^3 + Y'_vvr v'^2 r' + Y'_vrr v' r'^2 + Y'_rrr r'^3
//   N'_H = N'_v v' + N'_r r' + N'_vvv v'^3 + N'_vvr v'^2 r' + N'_vrr v' r'^2 + N'_rrr r'^3
//   U = sqrt(u^2 + v^2), v' = v/U, r' = r L/U, beta = atan(-v/u).
// Propeller: X_P = (1 - t_P) rho n^2 D_P^4 K_T(J_P), K_T = k_0 + k_1 J_P + k_2 J_P^2,
//   J_P = u (1 - w_P)/(n D_P), (1 - w_P) = (1 - w_P0) [1 + (1 - exp(-C_1 |beta_P|)) (C_2 - 1)],
//   beta_P = beta - x'_P r', C_2 = C_2+ for beta_P > 0, else C_2-.
// Rudder: F_N = 1/2 rho A_R U_R^2 f_alpha sin alpha_R, alpha_R = delta + delta_0 - atan(v_R/u_R),
//   X_R = -(1 - t_R) F_N sin delta_e, Y_R = -(1 + a_H) F_N cos delta_e,
//   N_R = -(x_R + a_H x_H) F_N cos delta_e   (delta_e = delta + delta_0, x_R = x'_R L,
//   x_H = x'_H L), u_R = eps u (1 - w_P) sqrt(eta {1 + kappa [sqrt(1 + 8 K_T/(pi J_P^2)) - 1]}^2
//   + 1 - eta), v_R = U gamma_R beta_R, beta_R = beta - l'_R r', gamma_R = gamma_R+ for
//   beta_R > 0, else gamma_R-; eta = D_P / H_R.
// Added masses m_x = 1/2 rho L^2 d m'_x, m_y likewise, J_z = 1/2 rho L^4 d J'_z.
//
// States [x0 (north), y0 (east), psi, u, v, r]; inputs [delta (rad, + to starboard), n
// (propeller rate, 1/s)]; outputs [x0, y0, psi, u, v, r, U]. Parameters: the non-dimensional
// coefficients above (defaults: the KVLCC2 of the paper's Tables 2-4) and a rudder bias delta_0.
// The ship's dimensions (Ship) are given data, not parameters. The right-hand side fails where
// u < 0 or the propeller's flow term leaves its domain (a diverging fit); from rest (U below
// Ship::SpeedFloor) v' and r' are taken at the floor, where the hull forces vanish, so that a
// simulation may start a ship from rest.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "engine/model/model.h"

namespace vesselid::mmg {

// The ship's given data (defaults: the KVLCC2's 7 m model, Yasukawa & Yoshimura 2015 Table 1).
struct Ship {
  double length = 7.0;                // L_pp [m]
  double draft = 0.455;               // d [m]
  double displacement = 3.2724;       // volume [m^3]; m = rho volume
  double centre_of_gravity = 0.245;   // x_G [m] forward of midship
  double radius_of_gyration = 0.25;   // k_zz / L_pp; I_zG = m (k_zz)^2
  double propeller_diameter = 0.216;  // D_P [m]
  double rudder_area = 0.0539;        // A_R [m^2]
  double rudder_height = 0.345;       // H_R [m]
  double rudder_position = -0.5;      // x'_R = x_R / L_pp
  double water_density = 1000.0;      // rho [kg/m^3] (a towing tank's fresh water)

  double Mass() const { return water_density * displacement; }
  // 0.1 % of sqrt(g L): the speed below which the model holds its non-dimensional velocities.
  double SpeedFloor() const { return 1e-3 * std::sqrt(9.81 * length); }
  // 1/2 rho L^2 d: the scale of the non-dimensional masses and forces (x L).
  double MassScale() const { return 0.5 * water_density * length * length * draft; }
  bool IsValid(std::string* error) const;
};

struct Model {
  static constexpr int kNumStates = 6;   // x0, y0, psi, u, v, r
  static constexpr int kNumInputs = 2;   // delta, n
  static constexpr int kNumOutputs = 7;  // x0, y0, psi, u, v, r, U
  enum Parameter {
    kR0,
    kXvv,
    kXvr,
    kXrr,
    kXvvvv,
    kYv,
    kYr,
    kYvvv,
    kYvvr,
    kYvrr,
    kYrrr,
    kNv,
    kNr,
    kNvvv,
    kNvvr,
    kNvrr,
    kNrrr,
    kMx,
    kMy,
    kJz,
    kTp,
    kWp0,
    kK0,
    kK1,
    kK2,
    kXp,
    kC1,
    kC2Plus,
    kC2Minus,
    kTr,
    kAh,
    kXh,
    kEpsilon,
    kKappa,
    kLr,
    kGammaPlus,
    kGammaMinus,
    kFalpha,
    kDelta0,
    kNumParameters
  };

  Ship ship;

  ModelInfo Info() const;
  double SpeedFloor() const { return ship.SpeedFloor(); }

  // u_dot = [u', v', r'] from the forces X, Y, N (the mass matrix solved), for the simulator's
  // external disturbances as well as the right-hand side.
  template <class T>
  void Accelerations(const T* x, const T* p, const T& X, const T& Y, const T& N,
                     T* acceleration) const {
    const double m = ship.Mass(), scale = ship.MassScale(), L = ship.length;
    const double xg = ship.centre_of_gravity;
    const double izg = m * (ship.radius_of_gyration * L) * (ship.radius_of_gyration * L);
    const T mx = scale * p[kMx], my = scale * p[kMy], jz = scale * L * L * p[kJz];
    const T& u = x[3];
    const T& v = x[4];
    const T& r = x[5];
    acceleration[0] = (X + (m + my) * v * r + xg * m * r * r) / (m + mx);
    // [m + m_y, x_G m; x_G m, I_zG + x_G^2 m + J_z] [v'; r'] = [Y - (m + m_x) u r; N - x_G m u r]
    const T a11 = m + my, a22 = izg + xg * xg * m + jz;
    const double a12 = xg * m;
    const T b1 = Y - (m + mx) * u * r, b2 = N - xg * m * u * r;
    const T det = a11 * a22 - a12 * a12;
    acceleration[1] = (a22 * b1 - a12 * b2) / det;
    acceleration[2] = (a11 * b2 - a12 * b1) / det;
  }

  // The hull, propeller and rudder forces [X, Y, N] at state x with inputs u_in; false where
  // the state or the flow terms leave the model's domain.
  template <class T, class U>
  bool Forces(const T* x, const U* u_in, const T* p, T* force) const {
    using std::atan2;
    using std::cos;
    using std::exp;
    using std::sin;
    using std::sqrt;
    const T& u = x[3];
    const T& v = x[4];
    const T& r = x[5];
    const U& n = u_in[1];
    if (!(u >= 0.0) || !(n > 0.0)) return false;
    const double L = ship.length, d = ship.draft, rho = ship.water_density;
    const double dp = ship.propeller_diameter;
    // Below the speed floor (a ship starting from rest) the non-dimensional velocities are
    // taken at the floor, where the hull forces (~U^2) vanish; above it the model is exact.
    const double floor = SpeedFloor();
    T speed2 = u * u + v * v;
    if (speed2 < floor * floor) speed2 = T(floor * floor);
    const T speed = sqrt(speed2);
    const T vn = v / speed, rn = r * L / speed;
    // Drift angle; at rest (u = v = 0) taken as 0 with no derivative: atan2's Jet is 0/0 there.
    const T beta = (u > 0.0 || v != 0.0) ? atan2(-v, u) : T(0.0);
    const T v2 = vn * vn, r2 = rn * rn;
    const T xh = -p[kR0] + p[kXvv] * v2 + p[kXvr] * vn * rn + p[kXrr] * r2 + p[kXvvvv] * v2 * v2;
    const T yh = p[kYv] * vn + p[kYr] * rn + p[kYvvv] * v2 * vn + p[kYvvr] * v2 * rn +
                 p[kYvrr] * vn * r2 + p[kYrrr] * r2 * rn;
    const T nh = p[kNv] * vn + p[kNr] * rn + p[kNvvv] * v2 * vn + p[kNvvr] * v2 * rn +
                 p[kNvrr] * vn * r2 + p[kNrrr] * r2 * rn;
    const T dynamic = 0.5 * rho * L * d * speed2;
    // Propeller: wake fraction changed by the inflow angle at the propeller.
    const T beta_p = beta - p[kXp] * rn;
    const T c2 = beta_p > 0.0 ? p[kC2Plus] : p[kC2Minus];
    const T abs_beta_p = beta_p < 0.0 ? -beta_p : beta_p;
    const T wake = (1.0 - p[kWp0]) * (1.0 + (1.0 - exp(-p[kC1] * abs_beta_p)) * (c2 - 1.0));
    const T inflow = u * wake;  // u_P = u (1 - w_P); J_P = u_P / (n D_P)
    const T j = inflow / (n * dp);
    const T kt = p[kK0] + p[kK1] * j + p[kK2] * j * j;
    const T xp = (1.0 - p[kTp]) * rho * n * n * dp * dp * dp * dp * kt;
    // Rudder: inflow accelerated by the propeller slipstream and straightened by the hull;
    // u_P sqrt(1 + 8 K_T/(pi J^2)) = sqrt(u_P^2 + 8 K_T n^2 D_P^2 / pi), defined at rest.
    const T slip2 = inflow * inflow + 8.0 * kt * n * n * dp * dp / M_PI;
    if (!(slip2 > 0.0)) return false;
    const double eta = dp / ship.rudder_height;
    const T stream = (1.0 - p[kKappa]) * inflow + p[kKappa] * sqrt(slip2);
    const T ur = p[kEpsilon] * sqrt(eta * stream * stream + (1.0 - eta) * inflow * inflow);
    const T beta_r = beta - p[kLr] * rn;
    const T gamma = beta_r > 0.0 ? p[kGammaPlus] : p[kGammaMinus];
    const T vr = speed * gamma * beta_r;
    const T delta = u_in[0] + p[kDelta0];
    const T alpha = delta - atan2(vr, ur);
    const T fn = 0.5 * rho * ship.rudder_area * (ur * ur + vr * vr) * p[kFalpha] * sin(alpha);
    const T cos_delta = cos(delta);
    force[0] = dynamic * xh + xp - (1.0 - p[kTr]) * fn * sin(delta);
    force[1] = dynamic * yh - (1.0 + p[kAh]) * fn * cos_delta;
    force[2] = dynamic * L * nh - (ship.rudder_position * L + p[kAh] * p[kXh] * L) * fn * cos_delta;
    return true;
  }

  template <class T, class U>
  bool operator()(const T* x, const U* u_in, const T* p, T* xdot) const {
    T force[3];
    if (!Forces(x, u_in, p, force)) return false;
    using std::cos;
    using std::sin;
    const T c = cos(x[2]), s = sin(x[2]);
    xdot[0] = x[3] * c - x[4] * s;
    xdot[1] = x[3] * s + x[4] * c;
    xdot[2] = x[5];
    Accelerations(x, p, force[0], force[1], force[2], xdot + 3);
    using std::isfinite;
    return isfinite(xdot[3]) && isfinite(xdot[4]) && isfinite(xdot[5]);
  }

  template <class T, class U>
  void Output(const T* x, const U*, const T*, T* y) const {
    using std::sqrt;
    for (int i = 0; i < kNumStates; ++i) y[i] = x[i];
    // U = sqrt(u^2 + v^2); at rest its derivative is taken as 0, not sqrt's infinite one
    // times 0 (a held-out run started at rest would have no derivatives at all).
    const T speed2 = x[3] * x[3] + x[4] * x[4];
    y[6] = speed2 > 0.0 ? sqrt(speed2) : T(0.0);
  }

  // Unmeasured velocities from the track: u, v from the position rates turned into the body
  // frame (else u from the speed U, v = 0), r from the heading's rate.
  void GuessState(const double* y, const double* ydot, double* x) const;
};

}  // namespace vesselid::mmg

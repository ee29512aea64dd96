// Physical 3-DOF twin-propeller catamaran (Fossen form), the data generator for the seed-000
// input-gain problem; double precision only, it is not the identified model.
//
//   state x = [n e psi u v r T_L T_R],  inputs: normalised PWM u_L, u_R in [-1, 1]
//
//   n' = u cos psi - v sin psi,   e' = u sin psi + v cos psi,   psi' = r
//   M nu' = tau + tau_wind - C(nu) nu - D(nu) nu,   nu = [u v r]
//   T_i' = (T_eff(u_i, u) - T_i) / tau_T
//
//   M     = M_RB + M_A,  M_RB = [[m,0,0],[0,m,m xg],[0,m xg,Iz]],
//           M_A = -[[Xudot,0,0],[0,Yvdot,Yrdot],[0,Nvdot,Nrdot]]
//   C nu  = C_RB nu + C_A nu with
//           C_RB = [[0,0,-m(xg r + v)],[0,0,m u],[m(xg r + v),-m u,0]],
//           C_A  = [[0,0,Yvdot v + Yrdot r],[0,0,-Xudot u],[-Yvdot v - Yrdot r,Xudot u,0]]
//   D nu  = -[Xu u + Xuu|u|u; Yv v + Yr r + Yvv|v|v; Nv v + Nr r + Nrr|r|r + Nuv u v]
//   tau   = [T_L + T_R, 0, lever (T_L - T_R)]   (left thrust turns the bow to starboard, r > 0)
//   tau_wind = R(psi)^T [F_n, F_e, 0]            (constant earth-fixed force)
//
// Static thrust T0(x): zero in the dead zone [d_r, d_f];
//   x > d_f:  Tmax_f (a s + (1 - a) s^2),  s = (x - d_f) / (1 - d_f)
//   x < d_r: -Tmax_r (a s + (1 - a) s^2),  s = (x - d_r) / (-1 - d_r)
// Thrust deduction with speed applies to forward thrust only: T_eff = T0 (1 - w u).
//
// Nuv u v is the viscous correction of the ideal-fluid Munk moment (Xudot - Yvdot) u v in
// C_A nu (flow separation at the sterns removes most of that couple). Without it (Nuv = 0)
// the straight run's sway-yaw linearisation has
//   det = Yv (Nr - (m xg - Yrdot) u) - (Yr - (m - Xudot) u) (Nv - (Xudot - Yvdot) u) < 0
// above u = 0.5 m/s: the craft is directionally unstable and equal thrusts end in a spin
// (r = 1.2 rad/s at full PWM). Nuv = Xudot - Yvdot = 12 cancels the Munk moment and leaves
// the craft course-stable at every speed.
#pragma once

namespace vesselid::input_gain {

enum CatamaranState { kN, kE, kPsi, kU, kV, kR, kTL, kTR, kCatamaranStates };

struct CatamaranParameters {
  double m = 30.0;      // kg
  double Iz = 4.5;      // kg m^2, about the origin
  double xg = 0.05;     // m, CG ahead of the origin
  double Xudot = -3.0;  // added mass (SNAME signs), kg, kg m, kg m^2
  double Yvdot = -15.0;
  double Yrdot = -0.8;
  double Nvdot = -0.8;
  double Nrdot = -1.8;
  double Xu = -5.0;  // linear damping: X = Xu u, Y = Yv v + Yr r, N = Nv v + Nr r
  double Yv = -25.0;
  double Yr = -2.0;
  double Nv = -1.0;
  double Nr = -4.0;
  double Xuu = -12.0;  // quadratic damping: X = Xuu |u| u, Y = Yvv |v| v, N = Nrr |r| r
  double Yvv = -70.0;
  double Nrr = -3.0;
  double Nuv = 12.0;                  // kg, Munk-moment correction N = Nuv u v (see above)
  double lever = 0.35;                // m, half the propeller spacing
  double thrust_forward = 40.0;       // N, Tmax_f at full forward PWM
  double thrust_reverse = 30.0;       // N, Tmax_r at full reverse PWM
  double linear_share = 0.35;         // a: linear part of the thrust curve
  double dead_forward = 0.04;         // d_f
  double dead_reverse = -0.04;        // d_r
  double thrust_deduction = 0.1;      // w, s/m: forward thrust T0 (1 - w u)
  double motor_time_constant = 0.25;  // tau_T, s
  double wind_north = 0.4;            // N, constant earth-fixed disturbance force
  double wind_east = 0.25;            // N
};

// T0(pwm), the static thrust of one propeller at rest.
double StaticThrust(const CatamaranParameters& p, double pwm);

// T0 (1 - w u) for forward thrust, T0 for reverse: the thrust the motor lag tends to.
double EffectiveThrust(const CatamaranParameters& p, double pwm, double u);

// x' for state x (kCatamaranStates values) and pwm = [u_L, u_R]; false when x or x' is not
// finite or M is singular.
bool CatamaranDerivative(const CatamaranParameters& p, const double* x, const double* pwm,
                         double* xdot);

}  // namespace vesselid::input_gain

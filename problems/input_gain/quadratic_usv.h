// A second twin-thruster vessel, built so that its structure is not the identified
// input-gain model's: a test of what the engine does when the model is wrong in the ways real
// craft make it wrong. Double precision only.
//
//   state x = [n e psi u v r w_L w_R],  inputs: normalised PWM u_L, u_R in [-1, 1]
//
//   Propeller speed (normalised) follows its command with a lag: w_i' = (u_i - w_i) / tau_w.
//   Thrust is purely quadratic with different ahead and astern coefficients (no linear term,
//   no dead zone): T_i = k_ahead w_i |w_i| for w_i >= 0, k_astern w_i |w_i| otherwise.
//   M nu' = tau - C_RB(nu) nu - C_A(nu) nu - D nu - d_cf(nu)   (calm water, no wind)
//     C_A nu carries the full ideal-fluid Munk moment (Xudot - Yvdot) u v;
//     D nu = -[Xu u + Xuu |u| u; Yv v + Yr r; Nv v + Nr r] (linear in sway and yaw);
//     d_cf: cross-flow drag of the two hulls by strip theory,
//       Y_cf = -c  sum_j |v + x_j r| (v + x_j r) dx,  N_cf = -c sum_j x_j |v + x_j r| (v + x_j r)
//       dx over strips x_j along the hull length, c = 1/2 rho C_d draft x 2 hulls.
//   tau = [T_L + T_R, 0, lever (T_L - T_R)].
#pragma once

#include "problems/input_gain/catamaran.h"

namespace vesselid::input_gain {

enum QuadraticUsvState { kWL = kTL, kWR = kTR, kQuadraticUsvStates = kCatamaranStates };

struct QuadraticUsvParameters {
  double m = 28.0;  // kg
  double Iz = 4.0;  // kg m^2 (CG at the origin)
  double Xudot = -2.5;
  double Yvdot = -5.0;
  double Yrdot = -0.5;
  double Nvdot = -0.5;
  double Nrdot = -1.5;
  double Xu = -3.0;
  double Xuu = -9.0;
  double Yv = -30.0;
  double Yr = -1.0;
  double Nv = 4.0;
  double Nr = -14.0;
  double hull_length = 1.6;     // m
  double cross_flow = 82.0;     // c = 1/2 rho C_d draft x 2 hulls, kg/m^2 (C_d 0.8, 0.1 m)
  double lever = 0.35;          // m
  double thrust_ahead = 32.0;   // N at w = 1
  double thrust_astern = 18.0;  // N at w = -1
  double propeller_lag = 0.1;   // tau_w, s
};

// T_i for propeller speed w.
double QuadraticThrust(const QuadraticUsvParameters& p, double w);

// x' for state x (kQuadraticUsvStates values) and pwm = [u_L, u_R]; false when x or x' is not
// finite.
bool QuadraticUsvDerivative(const QuadraticUsvParameters& p, const double* x, const double* pwm,
                            double* xdot);

}  // namespace vesselid::input_gain

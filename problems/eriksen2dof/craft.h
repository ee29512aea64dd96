// Physical planing craft like seed 004's Telemetron ASV (8.45 m, 1675 kg, 225 HP outboard,
// up to 18 m/s): the data generator ("truth") for the eriksen2dof model, which only
// approximates it. Double precision only; it is not the identified model.
//
//   state x = [N E psi u v r T delta]: position (m, north/east), heading (rad), velocity through
//   the water in body axes (u forward, v starboard, m/s), yaw rate (rad/s, r > 0 turns to
//   starboard), outboard thrust (N) and outboard angle (rad);
//   inputs tau = [tau_m in [0, 1] (throttle, always in forward gear), tau_delta in [-1, 1]]
//   (clamped to those ranges); environment: uniform current c and wind w (earth-fixed
//   velocities, m/s; gusts are the caller's business).
//
//   N' = u cos psi - v sin psi + c_N,   E' = u sin psi + v cos psi + c_E,   psi' = r
//   m_u u' = T cos delta - R(u) + m_v v r - k_turn m u r^2 + X_a
//   m_v v' = -m_u u r - (Y_v + Y_vu |u|) v - Y_vv |v| v - T sin delta + Y_a
//   I_r r' = l_p T sin delta - (N_r + N_ru |u|) r - N_rrr r^3 + x_a Y_a
//   T'     = (T_c(tau_m) - T) / t_motor
//   delta' = (delta_max tau_delta - delta) / t_rudder
//
// Sign convention: delta > 0 swings the propeller's thrust line so that it pushes the stern to
// port (side force -T sin delta at the transom, l_p behind the CG), which turns the bow to
// starboard: tau_delta > 0 gives r > 0 (heading increasing clockwise, NED).
//
// Motor: T_c = T_idle + (T_max - T_idle) g(tau_m), g piecewise linear through (0, 0),
// (tau_knee, g_knee), (1, 1) with the slope above the knee a factor knee_slope_ratio below the
// slope under it (the seed: "motor response is greatly reduced for tau_m > 0.6").
//
// Hull resistance across displacement, hump (Froude ~0.5) and planing regimes:
//   R(u) = sign(u) A (tanh((|u| - u_h) / w_h) + tanh(u_h / w_h)) + c_1 u + c_2 |u| u,
// strictly increasing (no fold: every throttle has one steady speed); the hump sigmoid is
// steep near u_h (short surge time constant) and flat above it before c_2 u^2 takes over (long
// time constant), so m_u / R'(u) varies several-fold across the regimes.
//
// Air: apparent wind a = R(psi)^T (w - [N' E']) in body axes,
//   X_a = k_x |a| a_x,  Y_a = k_y |a| a_y,  k = 1/2 rho_air C A;
// in still air this is the craft's own air drag -k_x u^2 (included in the top speed).
// The sway and yaw equations are symmetric in (v, r, delta) -> -(v, r, delta) apart from the
// wind, and the current moves the craft without changing u, v, r (uniform current), so in
// still water and calm air the steady map (tau_m, tau_delta) -> (U, r) is mirror symmetric.
#pragma once

namespace vesselid::eriksen2dof {

enum CraftState {
  kCraftN,
  kCraftE,
  kCraftPsi,
  kCraftU,
  kCraftV,
  kCraftR,
  kCraftThrust,
  kCraftAngle,
  kCraftStates
};

struct CraftParameters {
  double m = 1675.0;                 // kg, mass (Telemetron ASV)
  double m_u = 1775.0;               // kg, surge mass m - X_udot
  double m_v = 2200.0;               // kg, sway mass m - Y_vdot
  double I_r = 8500.0;               // kg m^2, yaw inertia I_z - N_rdot
  double thrust_idle = 95.0;         // N, T_idle: thrust at tau_m = 0 (in gear), about 1.9 m/s
  double thrust_max = 5100.0;        // N, T_max at tau_m = 1, about 18 m/s straight ahead
  double throttle_knee = 0.6;        // tau_knee, where the motor response flattens
  double knee_slope_ratio = 4.0;     // slope of g below the knee / slope above it
  double motor_time_constant = 1.0;  // s, t_motor
  double rudder_max = 30.0 * 0.017453292519943295;  // rad, delta_max (30 deg)
  double rudder_time_constant = 0.4;                // s, t_rudder
  double hump_force = 900.0;                        // N, A: half the resistance step of the hump
  double hump_speed = 4.5;                          // m/s, u_h: hump centre (Froude 0.49 on 8.45 m)
  double hump_width = 1.2;                          // m/s, w_h
  double drag_linear = 20.0;                        // N s/m, c_1
  double drag_quadratic = 7.5;                      // N s^2/m^2, c_2
  double turn_drag = 0.15;                // s, k_turn: induced drag k_turn m u r^2 in turns
  double sway_damping = 1500.0;           // N s/m, Y_v
  double sway_damping_speed = 1000.0;     // N s^2/m^2, Y_vu: hull lift grows with speed
  double sway_damping_quadratic = 600.0;  // N s^2/m^2, Y_vv
  double yaw_damping = 500.0;             // N m s, N_r
  double yaw_damping_speed = 900.0;       // N s^2, N_ru
  double yaw_damping_cubic = 30000.0;     // N m s^3, N_rrr: saturates the steady yaw rate
  double thrust_lever = 3.5;              // m, l_p: transom (propeller) behind the CG
  double air_drag_x = 1.4;  // kg/m, k_x = 1/2 rho_air C_x A_front (1.2 x 0.6 x 4 m^2 / 2)
  double air_drag_y = 4.5;  // kg/m, k_y = 1/2 rho_air C_y A_side (1.2 x 0.75 x 10 m^2 / 2)
  double wind_lever = 0.3;  // m, x_a: centre of side wind pressure ahead of the CG
};

// Instantaneous surroundings: uniform current and wind, earth-fixed velocities (the
// direction each moves towards), m/s. Zero is still water and calm air.
struct CraftEnvironment {
  double current_n = 0.0;
  double current_e = 0.0;
  double wind_n = 0.0;
  double wind_e = 0.0;
};

// g(tau_m) in [0, 1], tau_m clamped to [0, 1].
double ThrottleCurve(const CraftParameters& p, double tau_m);

// T_c(tau_m) = T_idle + (T_max - T_idle) g(tau_m), N.
double CommandedThrust(const CraftParameters& p, double tau_m);

// R(u), N.
double HullResistance(const CraftParameters& p, double u);

// m_u / (R'(u) + 2 k_x u): the straight-run surge time constant at speed u in still air
// (motor lag excluded), s.
double SurgeTimeConstant(const CraftParameters& p, double u);

// x' for state x (kCraftStates values), tau = [tau_m, tau_delta] and the environment; false
// when x or x' is not finite.
bool CraftDerivative(const CraftParameters& p, const double* x, const double* tau,
                     const CraftEnvironment& environment, double* xdot);

// Speed over ground and course over ground (rad, atan2(E', N')) of state x.
void GroundTrack(const double* x, const CraftEnvironment& environment, double* sog, double* course);

// The right-hand side as an Rk4Step model (engine/model/rk4.h); holds pointers, not copies.
struct CraftRhs {
  static constexpr int kNumStates = kCraftStates;
  const CraftParameters* parameters;
  const CraftEnvironment* environment;
  bool operator()(const double* x, const double* tau, const double*, double* xdot) const {
    return CraftDerivative(*parameters, x, tau, *environment, xdot);
  }
};

// Steady state for constant commands in still water and calm air (found by integrating from
// a straight run at the balance speed, then polished by Newton on u, v, r).
struct CraftSteadyState {
  double u = 0.0, v = 0.0, r = 0.0;  // m/s, m/s, rad/s
  double thrust = 0.0, angle = 0.0;  // N, rad
  double sog = 0.0;                  // m/s, |(u, v)|
};

// False when no steady state was found (not finite or not converged).
bool SteadyState(const CraftParameters& p, double tau_m, double tau_delta,
                 CraftSteadyState* steady);

}  // namespace vesselid::eriksen2dof

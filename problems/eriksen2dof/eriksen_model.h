// Eriksen-Breivik 2-DOF speed/yaw-rate model (MODELS.md §4, seed 004 eq. (4)).
//
// States x = [N, E, chi, U, r] (position, course over ground, speed over ground, yaw rate);
// inputs tau = [tau_m (throttle, 0..1), tau_delta (rudder, -1..1)]; every state is an output.
//
//   m_U(U, r) U' + sigma_U(U, r) = tau_m
//   m_r(U, r) r' + sigma_r(U, r) = tau_delta
//   N' = U cos chi,  E' = U sin chi,  chi' = r          (sideslip neglected)
//
//   sigma_j = phi(u, v)^T beta_sigma_j        phi: the 15 monomials of degree <= 4
//   m_j     = phi(u, v)^T beta_m_j + beta_m_j,tanh tanh(a_j (U - b_j))
//
// in the scaled states u = U / speed_scale, v = r / yaw_rate_scale (known constants, so that
// the coefficients are of order one). Parameters, in order: sigma_U.<monomial> (15),
// sigma_r.<monomial> (15), m_U.<monomial> (15), m_U.tanh, m_r.<monomial> (15), m_r.tanh,
// m_U.a, m_U.b, m_r.a, m_r.b (a in s/m, b in m/s); monomials named 1, U, r, U2, Ur, r2, U3, ...
//
// The simulation fails (returns false) where an inertia is not positive.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "engine/model/damping_inertia_form.h"
#include "engine/model/model.h"
#include "engine/model/polynomial_basis.h"

namespace vesselid::eriksen2dof {

struct Model {
  static constexpr int kNumStates = 5;   // N, E, chi, U, r
  static constexpr int kNumInputs = 2;   // tau_m, tau_delta
  static constexpr int kNumOutputs = 5;  // = states
  static constexpr int kDegree = 4;
  static constexpr int kBasis = NumMonomials(kDegree);  // 15
  // Parameter offsets.
  static constexpr int kSigmaU = 0;
  static constexpr int kSigmaR = kSigmaU + kBasis;
  static constexpr int kInertiaU = kSigmaR + kBasis;        // kBasis + 1 (tanh last)
  static constexpr int kInertiaR = kInertiaU + kBasis + 1;
  static constexpr int kAsymptote = kInertiaR + kBasis + 1;  // a_U, b_U, a_r, b_r
  static constexpr int kNumParameters = kAsymptote + 4;      // 66

  double speed_scale = 10.0;    // m/s
  double yaw_rate_scale = 0.5;  // rad/s

  ModelInfo Info() const;
  DampingInertiaForm DampingInertia() const;

  template <class T, class U>
  bool operator()(const T* x, const U* u, const T* p, T* xdot) const {
    T phi[kBasis];
    Monomials(kDegree, x[3] / speed_scale, x[4] / yaw_rate_scale, phi);
    T sigma_u = p[kSigmaU] * phi[0], sigma_r = p[kSigmaR] * phi[0];
    T m_u = p[kInertiaU] * phi[0], m_r = p[kInertiaR] * phi[0];
    for (int k = 1; k < kBasis; ++k) {
      sigma_u += p[kSigmaU + k] * phi[k];
      sigma_r += p[kSigmaR + k] * phi[k];
      m_u += p[kInertiaU + k] * phi[k];
      m_r += p[kInertiaR + k] * phi[k];
    }
    using std::tanh;
    m_u += p[kInertiaU + kBasis] * tanh(p[kAsymptote] * (x[3] - p[kAsymptote + 1]));
    m_r += p[kInertiaR + kBasis] * tanh(p[kAsymptote + 2] * (x[3] - p[kAsymptote + 3]));
    if (!(m_u > 0.0) || !(m_r > 0.0)) return false;
    using std::cos;
    using std::sin;
    xdot[0] = x[3] * cos(x[2]);
    xdot[1] = x[3] * sin(x[2]);
    xdot[2] = x[4];
    xdot[3] = (u[0] - sigma_u) / m_u;
    xdot[4] = (u[1] - sigma_r) / m_r;
    return true;
  }

  template <class T, class U>
  void Output(const T* x, const U*, const T*, T* y) const {
    for (int i = 0; i < kNumOutputs; ++i) y[i] = x[i];
  }
};

}  // namespace vesselid::eriksen2dof

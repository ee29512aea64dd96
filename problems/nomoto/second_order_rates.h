// Second-order Nomoto model that can be course-unstable (type second_order_rates, MODELS.md
// §2). Input: rudder angle delta [rad]. Outputs: heading psi [rad] and yaw rate r [rad/s].
//
// Nomoto's T1 T2 psi''' + (T1 + T2) psi'' + psi' = K (delta + T3 delta') divided by T1 T2:
//
//   psi''' + a1 psi'' + a0 psi' = b (delta + delta_0 + T3 delta')
//
//   a1 = 1/T1 + 1/T2   [1/s]    minus the sum of the yaw poles
//   a0 = 1/(T1 T2)     [1/s^2]  their product
//   b  = K/(T1 T2)     [1/s^2]  the rudder's yaw acceleration per radian (K a0)
//
// Every coefficient stays finite when a pole crosses zero, where T1 and K pass through
// infinity: a0 < 0 is a course-unstable (spiral-unstable) ship, one pole at
// (-a1 + sqrt(a1^2 - 4 a0)) / 2 > 0; a0 > 0 and a1 > 0 a stable one, with
// 1/T1, 1/T2 = (a1 -+ sqrt(a1^2 - 4 a0)) / 2 and K = b / a0. There is no T1 = T2 ridge and
// no exchange symmetry. Realised without delta' as
//
//   eta1' = eta2,  eta2' = b (delta + delta_0) - a0 eta1 - a1 eta2,
//   r = eta1 + T3 eta2,  psi' = r.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/model/model.h"
#include "problems/nomoto/nomoto_models.h"

namespace vesselid::nomoto {

struct SecondOrderRates {
  static constexpr int kNumStates = 3;  // psi, eta1, eta2
  static constexpr int kMaxParameters = 5;  // a1, a0, b, T3, delta_0
  static constexpr int kNumInputs = 1;  // delta
  static constexpr int kNumOutputs = 2;

  ModelInfo Info() const {
    // Default: the seed 003 cargo vessel (T1 45 s, T2 6 s, K 0.09 1/s).
    return WithParameterUnits({"nomoto_second_order_rates",
                               {"psi", "eta1", "eta2"},
                               {"delta"},
                               {"psi", "r"},
                               {"a1", "a0", "b", "T3", "delta_0"},
                               {1.0 / 45 + 1.0 / 6, 1.0 / 270, 0.09 / 270, 10.0, 0.0},
                               {true, false},
                               {},
                               {},
                               {"rad", "rad/s"},
                               {"rad", "rad/s", "rad/s^2"},  // r = eta1 + T3 eta2, eta2 = eta1'
                               {"rad"}},
                              {"1/s", "1/s^2", "1/s^3", "s", "rad"});
  }

  template <class T, class U>
  bool operator()(const T* x, const U* u, const T* p, T* xdot) const {
    xdot[0] = x[1] + p[3] * x[2];
    xdot[1] = x[2];
    xdot[2] = p[2] * (u[0] + p[4]) - p[1] * x[1] - p[0] * x[2];
    return true;
  }

  template <class T, class U>
  void Output(const T* x, const U*, const T* p, T* y) const {
    y[0] = x[0];
    y[1] = x[1] + p[3] * x[2];
  }

  // A ship has at most one unstable yaw pole: a1 <= 0 with a0 > 0 puts both in the right
  // half plane (a growing yaw oscillation), which no hull does.
  std::vector<std::string> Admissibility(const double* p, const double* = nullptr) const {
    if (p[0] > 0.0 || p[1] <= 0.0) return {};
    char text[160];
    std::snprintf(text, sizeof(text), "a1 = %.4g <= 0 with a0 = %.4g > 0: both yaw poles unstable",
                  p[0], p[1]);
    return {text};
  }
};

}  // namespace vesselid::nomoto

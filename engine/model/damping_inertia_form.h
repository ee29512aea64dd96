// The damping-inertia form of a model (seed 004 eq. (4)), for the step-regression stage:
//
//   M(x) x' + sigma(x) = tau,   M(x) = diag(m_i(x)),   one input tau_i per regressed state x_i
//   sigma_i(x) = phi(z)^T beta_sigma_i
//   m_i(x)     = phi(z)^T beta_m_i + beta_m_i,tanh tanh(a_i (x_s - b_i))
//
// phi the complete polynomial basis of polynomial_basis.h in the scaled states
// z_j = x_j / scale_j (two regressed states), x_s the state of the asymptotic term (speed).
// At a steady state sigma(x) = tau: the damping terms are measured by the inputs; a step of
// tau_i measures m_i (first_order_step.h).
//
// A model opts in with `DampingInertiaForm DampingInertia() const;` (see ModelHandle).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "engine/model/polynomial_basis.h"

namespace vesselid {

struct DampingInertiaForm {
  int degree = 4;
  std::vector<int> states;      // the two regressed states (model state indices)
  std::vector<int> inputs;      // tau_i driving state i (model input indices)
  std::vector<double> scale;    // z_i = x_i / scale_i in the basis
  // Parameter indices: damping[i] has NumMonomials(degree) entries, inertia[i] one more (the
  // coefficient of the asymptotic term, last); asymptote_a/b[i] the term's a_i, b_i.
  std::vector<std::vector<int>> damping;
  std::vector<std::vector<int>> inertia;
  std::vector<int> asymptote_a, asymptote_b;
  int asymptote_state = 0;  // index into `states` of x_s (a_i, b_i in its physical units)
  // Index into `states` of the yaw rate: the response is symmetric under
  // (x_turn, tau_turn) -> -(x_turn, tau_turn), and steady windows are judged by how many turns
  // they cover. -1: none.
  int turning_state = -1;
  std::vector<std::string> term_names;  // sigma_i then m_i, e.g. sigma_U, sigma_r, m_U, m_r

  int num_basis() const { return NumMonomials(degree); }
};

// sigma_i and m_i (i over the regressed states) at regressed states x, parameters p in model
// order. Not for the integration hot path: models evaluate their own terms.
inline void EvaluateDampingInertia(const DampingInertiaForm& form, const double* p,
                                   const double* x, double* sigma, double* m) {
  const int nb = form.num_basis();
  std::vector<double> phi(nb);
  Monomials(form.degree, x[0] / form.scale[0], x[1] / form.scale[1], phi.data());
  for (size_t i = 0; i < form.states.size(); ++i) {
    sigma[i] = 0.0;
    m[i] = 0.0;
    for (int k = 0; k < nb; ++k) {
      sigma[i] += p[form.damping[i][k]] * phi[k];
      m[i] += p[form.inertia[i][k]] * phi[k];
    }
    const double xs = x[form.asymptote_state];
    m[i] += p[form.inertia[i][nb]] *
            std::tanh(p[form.asymptote_a[i]] * (xs - p[form.asymptote_b[i]]));
  }
}

// A grid over the two regressed states on which the terms are tabulated (seed 004 Figs. 8-9).
struct SurfaceGrid {
  double lower[2] = {0.0, 0.0}, upper[2] = {0.0, 0.0};
  int points[2] = {0, 0};  // 0: no surfaces

  bool enabled() const { return points[0] > 0 && points[1] > 0; }
};

}  // namespace vesselid

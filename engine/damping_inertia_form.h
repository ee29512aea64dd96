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
#include <cstdio>
#include <string>
#include <vector>

#include "engine/polynomial_basis.h"

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

// CSV text of sigma_i and m_i on the grid, one row per point ("<state0>,<state1>,<terms>"),
// the second state varying fastest.
inline std::string SurfacesCsv(const DampingInertiaForm& form,
                               const std::vector<std::string>& state_names, const double* p,
                               const SurfaceGrid& grid) {
  std::string out = state_names[form.states[0]] + "," + state_names[form.states[1]];
  for (const std::string& name : form.term_names) out += "," + name;
  out += "\n";
  char field[32];
  for (int i = 0; i < grid.points[0]; ++i) {
    for (int j = 0; j < grid.points[1]; ++j) {
      double x[2];
      const int at[2] = {i, j};
      for (int c = 0; c < 2; ++c) {
        x[c] = grid.points[c] == 1 ? grid.lower[c]
                                   : grid.lower[c] + (grid.upper[c] - grid.lower[c]) * at[c] /
                                                         (grid.points[c] - 1);
      }
      double sigma[2], m[2];
      EvaluateDampingInertia(form, p, x, sigma, m);
      const double row[6] = {x[0], x[1], sigma[0], sigma[1], m[0], m[1]};
      for (int c = 0; c < 6; ++c) {
        std::snprintf(field, sizeof(field), "%.10g", row[c]);
        out += (c == 0 ? "" : ",") + std::string(field);
      }
      out += "\n";
    }
  }
  return out;
}

}  // namespace vesselid

// What the engine's own trust-region minimisers of 1/2 |f(x)|^2 within bounds l <= x <= u
// share: the n x n quantities each trial point is evaluated to (the cost, J'f and J'J, so that
// a long record costs one pass over its Jacobian per trial point and the step no more than an
// n x n factorisation), their options, callback and summary. The methods:
// reflective_trust_region.h (Branch, Coleman & Li) and levenberg_marquardt.h (Ceres' damping
// and radius rules, bounds by projection).
#pragma once

#include <cmath>
#include <functional>
#include <string>

#include "Eigen/Dense"
#include "engine/base/elapsed.h"

namespace vesselid {

struct DenseSolveOptions {
  int max_evaluations = 200;  // trial points (each evaluates residuals and Jacobian)
  // Stopping rules (each method's header says how it applies them): a step that changes the
  // cost by less than function_tolerance x cost, a step shorter than parameter_tolerance x
  // (parameter_tolerance + |x|), a (scaled or projected) gradient below gradient_tolerance.
  double function_tolerance = 1e-12;
  double parameter_tolerance = 1e-12;
  double gradient_tolerance = 1e-14;
  double max_time_seconds = 3600.0;
  // Reflective: scales each unknown by its Jacobian column's norm (the largest seen so far),
  // as Marquardt's damping does: the trust region is then the same for any units of the
  // unknowns. Off: the unknowns as given (the engine's value / scale). Levenberg-Marquardt
  // always scales (Ceres' Jacobi scaling, from the start's Jacobian).
  bool jacobian_scaling = true;
  // Levenberg-Marquardt: the first radius (the first step is damped by 1/radius).
  double initial_radius = 1e4;
};

// What the solve needs of the residuals f (size m) and their Jacobian J at a point: the
// cost, 1/2 |f|^2 (or the robustified cost when f and J are the loss's corrected ones, whose
// Gauss-Newton gradient J'f is exact), g = J'f and J'J.
struct NormalEquations {
  double cost = 0.0;
  Eigen::VectorXd gradient;
  Eigen::MatrixXd normal;
  int residuals = 0;  // m
};

// Evaluates them at x; false when they cannot be evaluated (a step the solve then shortens).
using NormalEquationsFunction = std::function<bool(const Eigen::VectorXd& x, NormalEquations* out)>;

// At the start (trial 0) and after each trial point (1, 2, ...): whether it was accepted, the
// cost at the current iterate and the iterate. Returns 0 to go on, 1 to stop successfully, -1 to
// abandon.
using TrialCallback =
    std::function<int(int trial, bool accepted, double cost, const Eigen::VectorXd& x)>;

struct DenseSolveSummary {
  enum class End {
    kConvergence,    // a tolerance was met
    kNoConvergence,  // max_evaluations or max_time_seconds
    kUserSuccess,    // the callback stopped it
    kUserFailure,    // the callback abandoned it
    kFailure,        // the start could not be evaluated, or no step could be formed
  };
  End end = End::kFailure;
  std::string message;
  double initial_cost = -1.0;
  double final_cost = -1.0;
  int evaluations = 0;
  int accepted = 0;
  int rejected = 0;  // a worse cost, or residuals that could not be evaluated
  double evaluation_seconds = 0.0;
  double step_seconds = 0.0;  // the factorisations and step selection
  double total_seconds = 0.0;
};

// f at x, counted and timed in *summary; false when f fails or gives a non-finite cost,
// gradient or normal matrix.
inline bool EvaluateTrial(const NormalEquationsFunction& f, const Eigen::VectorXd& x,
                          NormalEquations* e, DenseSolveSummary* summary) {
  const auto start = SteadyClock::now();
  ++summary->evaluations;
  const bool ok =
      f(x, e) && std::isfinite(e->cost) && e->gradient.allFinite() && e->normal.allFinite();
  summary->evaluation_seconds += SecondsSince(start);
  return ok;
}

}  // namespace vesselid

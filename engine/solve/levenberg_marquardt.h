// Levenberg-Marquardt on the normal equations (dense_trust_region.h): Ceres' method (its
// Jacobi scaling, damping and radius rules) at the price of one evaluation per trial point.
//
// With S = diag(1 / (1 + |J_j|)) from the start's Jacobian (Ceres' Jacobi scaling), each
// trial solves
//
//   (S J'J S + diag(d) / radius) y = -S J'f,   step = S y,   d = clamp(diag(S J'J S), 1e-6, 1e32)
//
// (d refreshed after each accepted step), projects x + step onto the bounds and accepts it
// when the cost falls by more than 1e-3 of what the model predicts for the projected step. On
// success radius /= max(1/3, 1 - (2 rho - 1)^3); on failure, or where the residuals cannot
// be evaluated (a simulation that diverged), radius /= 2, 4, 8, ... . Ceres' minimiser under
// bounds adds a projected line search whose gradient at every candidate is a second Jacobian
// evaluation there; this one has none, so an iteration costs its one Jet simulation.
//
// Stops (converged) when the projected gradient |x - P(x - g)|_inf is at most
// gradient_tolerance, a step changes the cost by at most function_tolerance x cost, the
// projected step is at most parameter_tolerance x (|x| + parameter_tolerance), or the
// radius falls below 1e-32.
#pragma once

#include "engine/solve/dense_trust_region.h"

namespace vesselid {

// Solves from *x (projected onto the bounds first) and leaves the last accepted iterate in *x.
// lower/upper may hold -inf/+inf. Uses options.initial_radius; not jacobian_scaling.
DenseSolveSummary SolveLevenbergMarquardt(const DenseSolveOptions& options,
                                          const NormalEquationsFunction& f,
                                          const Eigen::VectorXd& lower,
                                          const Eigen::VectorXd& upper,
                                          const TrialCallback& callback, Eigen::VectorXd* x);

}  // namespace vesselid

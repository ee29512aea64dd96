// A trust-region reflective minimiser of 1/2 |f(x)|^2 within bounds l <= x <= u (Branch,
// Coleman & Li, SIAM J. Sci. Comput. 21(1), 1999), the method of SciPy's least_squares('trf').
//
// Every iterate stays strictly inside the bounds. The trust region lives in a space scaled by
// Coleman-Li's vector v (v_i the distance to the bound the gradient pushes x_i toward, 1 when
// there is none), so that an unknown near such a bound takes short steps toward it:
//
//   min over h   1/2 |J D h + f|^2 + 1/2 h' diag(g dv) h,   |h| <= Delta,   D = diag(sqrt v),
//
// solved exactly (Moré's secular equation on the eigen-decomposition of the n x n normal
// matrix, the squared singular values of the augmented Jacobian). A step that
// leaves the box is cut at the bound and the best of three is taken: the cut step pulled
// inside, its reflection off the bound, and the scaled gradient step. The radius shrinks to a
// quarter of a step that predicted badly (or whose residuals could not be evaluated: a
// simulation that diverged) and doubles after a good step that reached it.
#pragma once

#include <functional>
#include <string>

#include "Eigen/Dense"

namespace vesselid {

struct ReflectiveOptions {
  int max_evaluations = 200;  // trial points (each evaluates residuals and Jacobian)
  // Stops when a step lowers the cost by less than function_tolerance x cost (and predicted
  // it well), or is shorter than parameter_tolerance x (parameter_tolerance + |x|), or when
  // the scaled gradient |v g|_inf falls below gradient_tolerance.
  double function_tolerance = 1e-12;
  double parameter_tolerance = 1e-12;
  double gradient_tolerance = 1e-14;
  double max_time_seconds = 3600.0;
  // Scales each unknown by its Jacobian column's norm (the largest seen so far), as
  // Marquardt's damping does: the trust region is then the same for any units of the
  // unknowns. Off: the unknowns as given (the engine's value / scale).
  bool jacobian_scaling = true;
};

// What the solve needs of the residuals f (size m) and their Jacobian J at a point: the
// cost, 1/2 |f|^2 (or the robustified cost when f and J are the loss's corrected ones, whose
// Gauss-Newton gradient J'f is exact), g = J'f and J'J. Each step works on these n x n
// quantities alone, so that a long record costs one pass over its Jacobian per evaluation.
struct NormalEquations {
  double cost = 0.0;
  Eigen::VectorXd gradient;
  Eigen::MatrixXd normal;
  int residuals = 0;  // m
};

// Evaluates them at x; false when they cannot be evaluated (a step the solve then shortens).
using ReflectiveFunction = std::function<bool(const Eigen::VectorXd& x, NormalEquations* out)>;

// At the start (trial 0) and after each trial point (1, 2, ...): whether it was accepted, the
// cost at the current iterate and the iterate. Returns 0 to go on, 1 to stop successfully, -1 to
// abandon.
using ReflectiveCallback =
    std::function<int(int trial, bool accepted, double cost, const Eigen::VectorXd& x)>;

struct ReflectiveSummary {
  enum class End {
    kConvergence,    // a tolerance was met
    kNoConvergence,  // max_evaluations or max_time_seconds
    kUserSuccess,    // the callback stopped it
    kUserFailure,    // the callback abandoned it
    kFailure,        // the start could not be evaluated
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

// Solves from *x (moved strictly inside the bounds first) and leaves the last accepted iterate
// in *x. lower/upper may hold -inf/+inf.
ReflectiveSummary SolveReflective(const ReflectiveOptions& options, const ReflectiveFunction& f,
                                  const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                  const ReflectiveCallback& callback, Eigen::VectorXd* x);

}  // namespace vesselid

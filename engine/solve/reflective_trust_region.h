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

#include "engine/solve/dense_trust_region.h"

namespace vesselid {

// Solves from *x (moved strictly inside the bounds first) and leaves the last accepted iterate
// in *x. lower/upper may hold -inf/+inf.
DenseSolveSummary SolveReflective(const DenseSolveOptions& options, const NormalEquationsFunction& f,
                                  const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                  const TrialCallback& callback, Eigen::VectorXd* x);

}  // namespace vesselid

#include "engine/solve/levenberg_marquardt.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/base/elapsed.h"

namespace vesselid {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// Ceres' defaults: min_lm_diagonal, max_lm_diagonal, max_trust_region_radius,
// min_trust_region_radius, min_relative_decrease.
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
constexpr double kMaxRadius = 1e16;
constexpr double kMinRadius = 1e-32;
constexpr double kMinRelativeDecrease = 1e-3;
// The radius from which a step is Gauss-Newton's within 0.1 %.
constexpr double kUndampedRadius = 1e3;
// Steps rejected in a row without an evaluation (no finite step, or a projected step the
// model does not expect to lower the cost) before the solve gives up.
constexpr int kMaxUnformedSteps = 60;

VectorXd Project(const VectorXd& x, const VectorXd& lower, const VectorXd& upper) {
  return x.cwiseMax(lower).cwiseMin(upper);
}

}  // namespace

DenseSolveSummary SolveLevenbergMarquardt(const DenseSolveOptions& options,
                                          const NormalEquationsFunction& f,
                                          const VectorXd& lower, const VectorXd& upper,
                                          const TrialCallback& callback, VectorXd* x_io) {
  using End = DenseSolveSummary::End;
  const auto begin = SteadyClock::now();
  DenseSolveSummary summary;
  VectorXd x = Project(*x_io, lower, upper);
  auto evaluate = [&](const VectorXd& point, NormalEquations* e) {
    return EvaluateTrial(f, point, e, &summary);
  };
  auto finish = [&](End end, const char* message) {
    summary.end = end;
    summary.message = message;
  };
  NormalEquations at, trial;
  if (!evaluate(x, &at)) {
    summary.message = "the residuals cannot be evaluated at the start";
    summary.total_seconds = SecondsSince(begin);
    return summary;
  }
  double cost = at.cost;
  summary.initial_cost = cost;
  bool done = false;
  auto ask = [&](int trial_index, bool accepted) {
    if (!callback) return;
    const int answer = callback(trial_index, accepted, cost, x);
    if (answer != 0) {
      finish(answer > 0 ? End::kUserSuccess : End::kUserFailure, "stopped by a callback");
      done = true;
    }
  };
  ask(0, true);
  // Ceres' Jacobi scaling, fixed at the start: s_j = 1 / (1 + |J_j|).
  auto jacobi_scale = [](const NormalEquations& e) -> VectorXd {
    return (1.0 + e.normal.diagonal().cwiseMax(0.0).cwiseSqrt().array()).inverse().matrix();
  };
  VectorXd scale = jacobi_scale(at);
  bool rescaled = false;  // the scale taken again at the current iterate
  double radius = options.initial_radius;
  double decrease = 2.0;
  VectorXd damping;  // d, refreshed after each accepted step
  bool refresh = true;
  int unformed = 0;
  int small_changes = 0;  // trial points in a row that changed the cost by < function_tolerance
  if (!done) finish(End::kNoConvergence, "the maximum number of evaluations was reached");
  while (!done) {
    const VectorXd projected_gradient = x - Project(x - at.gradient, lower, upper);
    if (projected_gradient.lpNorm<Eigen::Infinity>() <= options.gradient_tolerance) {
      finish(End::kConvergence, "the projected gradient is below gradient_tolerance");
      break;
    }
    if (summary.evaluations >= options.max_evaluations) break;
    if (SecondsSince(begin) > options.max_time_seconds) {
      finish(End::kNoConvergence, "the time limit was reached");
      break;
    }
    const auto step_start = SteadyClock::now();
    MatrixXd a = scale.asDiagonal() * at.normal * scale.asDiagonal();
    if (refresh) damping = a.diagonal().cwiseMax(kMinDiagonal).cwiseMin(kMaxDiagonal);
    refresh = false;
    a.diagonal() += damping / radius;
    VectorXd rhs = -scale.cwiseProduct(at.gradient);
    // An unknown on a bound that its gradient pushes it past stays there for this step (the
    // binding set of projected Newton methods): otherwise the step is formed as if it could
    // move, and its projection crawls along the bound.
    for (int i = 0; i < rhs.size(); ++i) {
      const bool binding = (x[i] <= lower[i] && at.gradient[i] > 0.0) ||
                           (x[i] >= upper[i] && at.gradient[i] < 0.0);
      if (!binding) continue;
      a.row(i).setZero();
      a.col(i).setZero();
      a(i, i) = 1.0;
      rhs[i] = 0.0;
    }
    const VectorXd y = a.ldlt().solve(rhs);
    const VectorXd x_new = Project(x + scale.cwiseProduct(y), lower, upper);
    const VectorXd p = x_new - x;
    // The model's reduction for the step taken: -(g'p + p'J'Jp / 2).
    const double predicted = -(at.gradient.dot(p) + 0.5 * p.dot(at.normal * p));
    summary.step_seconds += SecondsSince(step_start);
    auto reject = [&] {
      radius /= decrease;
      decrease *= 2.0;
    };
    if ((!y.allFinite() || !std::isfinite(predicted)) && !rescaled) {
      // The Jacobian has grown by orders of magnitude since the start (a simulation near a
      // blow-up), beyond what the damping's clamped diagonal can hold: scale from here.
      scale = jacobi_scale(at);
      refresh = true;
      rescaled = true;
      continue;
    }
    if (!y.allFinite() || !(predicted > 0.0)) {
      // No finite step; or, shortened until the binding set and the projection leave the
      // steepest descent over the free unknowns, still none the model expects to lower the
      // cost: the projected gradient is zero within rounding.
      reject();
      if (++unformed >= kMaxUnformedSteps || radius < kMinRadius) {
        if (!y.allFinite()) {
          finish(End::kFailure, "no finite step could be formed");
        } else if (p.isZero(0.0)) {
          // Not a stationary point: the steps the damping allows no longer move the unknowns.
          finish(End::kNoConvergence,
                 "the steps shrank below the unknowns' resolution where the gradient is still "
                 "large, as near a simulation's blow-up");
        } else {
          finish(End::kConvergence, "no step lowers the model: a stationary point within rounding");
        }
        break;
      }
      continue;
    }
    unformed = 0;
    if (p.norm() <= options.parameter_tolerance * (x.norm() + options.parameter_tolerance)) {
      finish(End::kConvergence, "the step is below parameter_tolerance");
      break;
    }
    bool accepted = false;
    if (!evaluate(x_new, &trial)) {
      ++summary.rejected;
      reject();
    } else {
      const double actual = cost - trial.cost;
      const double rho = actual / predicted;
      accepted = rho > kMinRelativeDecrease;
      // A step damped by more than 1e-3 (radius < 1e3: the damping is diag / radius) changes
      // the cost little because it is short, not because the cost is flat there: it ends the
      // solve only as the third such step in a row.
      const bool flat = std::abs(actual) <= options.function_tolerance * cost;
      small_changes = flat ? small_changes + 1 : 0;
      if (flat && (radius >= kUndampedRadius || small_changes >= 3)) {
        finish(End::kConvergence, "the cost changed by less than function_tolerance");
        done = true;
        accepted = actual > 0.0;
      }
      if (accepted) {
        x = x_new;
        cost = trial.cost;
        std::swap(at, trial);
        ++summary.accepted;
        rescaled = false;
        radius = std::min(kMaxRadius, radius / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3)));
        decrease = 2.0;
        refresh = true;
      } else {
        ++summary.rejected;
        reject();
      }
    }
    ask(summary.evaluations - 1, accepted);
    if (!done && radius < kMinRadius) {
      finish(End::kConvergence, "the trust region shrank to nothing");
      break;
    }
  }
  summary.final_cost = cost;
  *x_io = x;
  summary.total_seconds = SecondsSince(begin);
  return summary;
}

}  // namespace vesselid

#include "engine/solve/reflective_trust_region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "engine/base/elapsed.h"

namespace vesselid {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
constexpr double kNoBound = std::numeric_limits<double>::infinity();

// Coleman-Li scaling: v_i = distance to the bound that -g_i points at (1 without one) and
// dv_i = its derivative with respect to x_i (+-1, or 0).
void ScalingVector(const VectorXd& x, const VectorXd& g, const VectorXd& lower,
                   const VectorXd& upper, VectorXd* v, VectorXd* dv) {
  const int n = static_cast<int>(x.size());
  v->setOnes(n);
  dv->setZero(n);
  for (int i = 0; i < n; ++i) {
    if (g[i] < 0.0 && std::isfinite(upper[i])) {
      (*v)[i] = upper[i] - x[i];
      (*dv)[i] = -1.0;
    } else if (g[i] > 0.0 && std::isfinite(lower[i])) {
      (*v)[i] = x[i] - lower[i];
      (*dv)[i] = 1.0;
    }
  }
}

// Moves x inside the bounds by a relative `step` (0: to the next representable number).
VectorXd StrictlyFeasible(VectorXd x, const VectorXd& lower, const VectorXd& upper, double step) {
  for (int i = 0; i < x.size(); ++i) {
    if (x[i] <= lower[i]) {
      x[i] = step == 0.0 ? std::nextafter(lower[i], upper[i])
                         : lower[i] + step * std::max(1.0, std::abs(lower[i]));
    } else if (x[i] >= upper[i]) {
      x[i] = step == 0.0 ? std::nextafter(upper[i], lower[i])
                         : upper[i] - step * std::max(1.0, std::abs(upper[i]));
    }
    if (x[i] < lower[i] || x[i] > upper[i]) x[i] = 0.5 * (lower[i] + upper[i]);
  }
  return x;
}

// The largest t with x + t s inside the bounds, and which unknowns reach a bound there.
double StepToBound(const VectorXd& x, const VectorXd& s, const VectorXd& lower,
                   const VectorXd& upper, std::vector<bool>* hits = nullptr) {
  const int n = static_cast<int>(x.size());
  VectorXd steps = VectorXd::Constant(n, kNoBound);
  for (int i = 0; i < n; ++i) {
    if (s[i] != 0.0) steps[i] = std::max((lower[i] - x[i]) / s[i], (upper[i] - x[i]) / s[i]);
  }
  const double smallest = steps.minCoeff();
  if (hits != nullptr) {
    hits->assign(n, false);
    for (int i = 0; i < n; ++i) (*hits)[i] = steps[i] == smallest;
  }
  return smallest;
}

// The positive root t of |x + t s| = Delta (x inside the sphere).
double ToTrustRegion(const VectorXd& x, const VectorXd& s, double delta) {
  const double a = s.squaredNorm();
  const double b = x.dot(s);
  const double c = x.squaredNorm() - delta * delta;
  const double d = std::sqrt(std::max(0.0, b * b - a * c));
  const double q = -(b + std::copysign(d, b));
  if (q == 0.0) return 0.0;
  return std::max(q / a, c / q);
}

// The scaled model q(h) = 1/2 h' H h + g_h' h, H = D J'J D + diag(c) (the augmented
// problem's normal matrix).
struct ScaledModel {
  const MatrixXd& h;
  const VectorXd& gh;

  double Value(const VectorXd& step) const { return 0.5 * step.dot(h * step) + gh.dot(step); }
  // q(h0 + t s) = a t^2 + b t + q(h0).
  void Along(const VectorXd& s, const VectorXd& h0, double* a, double* b) const {
    const VectorXd hs = h * s;
    *a = 0.5 * s.dot(hs);
    *b = gh.dot(s) + h0.dot(hs);
  }
};

// The minimum of a t^2 + b t over [lo, hi]: t and the value.
std::pair<double, double> MinimizeOnInterval(double a, double b, double lo, double hi) {
  double best_t = lo, best = lo * (a * lo + b);
  auto consider = [&](double t) {
    const double y = t * (a * t + b);
    if (y < best) best = y, best_t = t;
  };
  consider(hi);
  if (a != 0.0) {
    const double extremum = -0.5 * b / a;
    if (lo < extremum && extremum < hi) consider(extremum);
  }
  return {best_t, best};
}

// The trust-region step of the augmented least-squares problem min |J_a h + f_a|, |h| <= Delta,
// from the eigen-decomposition of its normal matrix J_a'J_a = V diag(lambda) V' (lambda the
// squared singular values of J_a) and vg = V' J_a'f_a = V' g_h: h(alpha) = -V vg / (lambda +
// alpha) (Moré & Sorensen's secular equation on alpha, Newton's iteration safeguarded in
// [alpha_lower, alpha_upper]). *alpha is the previous solution on entry (0: none) and this
// one on exit.
VectorXd TrustRegionStep(const VectorXd& lambda, const MatrixXd& v, const VectorXd& vg,
                         int residuals, double delta, double* alpha) {
  const int n = static_cast<int>(lambda.size());
  const double largest = lambda.maxCoeff(), smallest = std::max(0.0, lambda.minCoeff());
  const bool full_rank = residuals >= n && n > 0 &&
                         std::sqrt(smallest) > std::numeric_limits<double>::epsilon() * residuals *
                                                   std::sqrt(std::max(0.0, largest));
  if (full_rank) {
    const VectorXd p = -v * vg.cwiseQuotient(lambda);
    if (p.norm() <= delta) {
      *alpha = 0.0;
      return p;
    }
  }
  auto phi = [&](double a, double* derivative) {
    const VectorXd denom = lambda.array() + a;
    const double p_norm = vg.cwiseQuotient(denom).norm();
    *derivative = -(vg.cwiseProduct(vg).array() / denom.array().cube()).sum() / p_norm;
    return p_norm - delta;
  };
  double upper = vg.norm() / delta;
  double lower = 0.0;
  if (full_rank) {
    double derivative = 0.0;
    const double value = phi(0.0, &derivative);
    lower = -value / derivative;
  }
  double a = *alpha;
  if (!full_rank && a == 0.0) a = std::max(1e-3 * upper, std::sqrt(lower * upper));
  for (int it = 0; it < 10; ++it) {
    if (a < lower || a > upper) a = std::max(1e-3 * upper, std::sqrt(lower * upper));
    double derivative = 0.0;
    const double value = phi(a, &derivative);
    if (value < 0.0) upper = a;
    const double ratio = value / derivative;
    lower = std::max(lower, a - ratio);
    a -= (value + delta) * ratio / delta;
    if (std::abs(value) < 0.01 * delta) break;
  }
  *alpha = a;
  VectorXd p = -v * vg.cwiseQuotient(VectorXd(lambda.array() + a));
  const double norm = p.norm();
  if (norm > 0.0) p *= delta / norm;
  return p;
}

// The chosen step in x and in the scaled space, and the reduction the model predicts.
struct Step {
  VectorXd x, h;
  double predicted = 0.0;
};

// Of the trust-region step p_h, if it leaves the box: the step cut at the bound and pulled
// back by theta, its reflection off the bound, and the scaled steepest descent within both
// regions; the one of the three the model rates lowest.
Step SelectStep(const VectorXd& x, const ScaledModel& model, VectorXd p_h, const VectorXd& d,
                double delta, const VectorXd& lower, const VectorXd& upper, double theta) {
  VectorXd p = d.cwiseProduct(p_h);
  const VectorXd moved = x + p;
  if (((moved.array() >= lower.array()) && (moved.array() <= upper.array())).all()) {
    return {p, p_h, -model.Value(p_h)};
  }
  std::vector<bool> hits;
  const double p_stride = StepToBound(x, p, lower, upper, &hits);
  VectorXd r_h = p_h;
  for (int i = 0; i < r_h.size(); ++i) {
    if (hits[i]) r_h[i] = -r_h[i];
  }
  VectorXd r = d.cwiseProduct(r_h);
  p *= p_stride;
  p_h *= p_stride;
  const VectorXd on_bound = x + p;
  // Along the reflection until the box or the trust region ends, strictly inside the box.
  const double to_region = ToTrustRegion(p_h, r_h, delta);
  const double to_bound = StepToBound(on_bound, r, lower, upper);
  const double r_stride = std::min(to_bound, to_region);
  double r_lo = 0.0, r_hi = -1.0;
  if (r_stride > 0.0) {
    r_lo = (1.0 - theta) * p_stride / r_stride;
    r_hi = r_stride == to_bound ? theta * to_bound : to_region;
  }
  double r_value = kNoBound;
  if (r_lo <= r_hi) {
    double a = 0.0, b = 0.0;
    model.Along(r_h, p_h, &a, &b);
    const double t = MinimizeOnInterval(a, b, r_lo, r_hi).first;
    r_h = p_h + t * r_h;
    r = d.cwiseProduct(r_h);
    r_value = model.Value(r_h);
  }
  p *= theta;
  p_h *= theta;
  const double p_value = model.Value(p_h);
  VectorXd ag_h = -model.gh;
  VectorXd ag = d.cwiseProduct(ag_h);
  const double ag_norm = ag_h.norm();
  double ag_value = kNoBound;
  if (ag_norm > 0.0) {
    const double to_tr = delta / ag_norm;
    const double bound = StepToBound(x, ag, lower, upper);
    const double stride = bound < to_tr ? theta * bound : to_tr;
    double a = 0.0, b = 0.0;
    model.Along(ag_h, VectorXd::Zero(ag_h.size()), &a, &b);
    const auto [t, value] = MinimizeOnInterval(a, b, 0.0, stride);
    ag_h *= t;
    ag *= t;
    ag_value = value;
  }
  if (p_value < r_value && p_value < ag_value) return {p, p_h, -p_value};
  if (r_value < p_value && r_value < ag_value) return {r, r_h, -r_value};
  return {ag, ag_h, -ag_value};
}

}  // namespace

DenseSolveSummary SolveReflective(const DenseSolveOptions& options, const NormalEquationsFunction& f,
                                  const VectorXd& lower, const VectorXd& upper,
                                  const TrialCallback& callback, VectorXd* x_io) {
  const auto begin = SteadyClock::now();
  DenseSolveSummary summary;
  VectorXd x = StrictlyFeasible(*x_io, lower, upper, 1e-10);
  const int n = static_cast<int>(x.size());
  NormalEquations at;
  auto evaluate = [&](const VectorXd& point, NormalEquations* e) {
    return EvaluateTrial(f, point, e, &summary);
  };
  if (!evaluate(x, &at)) {
    summary.message = "the residuals cannot be evaluated at the start";
    summary.total_seconds = SecondsSince(begin);
    return summary;
  }
  double cost = at.cost;
  summary.initial_cost = summary.final_cost = cost;
  if (callback) {
    const int answer = callback(0, true, cost, x);
    if (answer != 0) {
      summary.end =
          answer > 0 ? DenseSolveSummary::End::kUserSuccess : DenseSolveSummary::End::kUserFailure;
      summary.message = "stopped by a callback";
      summary.total_seconds = SecondsSince(begin);
      return summary;
    }
  }
  const int m = at.residuals;
  VectorXd g = at.gradient;
  // scale_inv: the norms of the Jacobian's columns, never decreasing (1 for a zero column).
  VectorXd scale_inv = VectorXd::Ones(n);
  auto update_scale = [&](bool first) {
    if (!options.jacobian_scaling) return;
    for (int i = 0; i < n; ++i) {
      const double norm = std::sqrt(std::max(0.0, at.normal(i, i)));
      scale_inv[i] = first ? (norm > 0.0 ? norm : 1.0) : std::max(scale_inv[i], norm);
    }
  };
  update_scale(true);
  VectorXd v, dv;
  ScalingVector(x, g, lower, upper, &v, &dv);
  for (int i = 0; i < n; ++i) {
    if (dv[i] != 0.0) v[i] *= scale_inv[i];
  }
  double delta = x.cwiseProduct(scale_inv).cwiseQuotient(v.cwiseSqrt()).norm();
  if (!(delta > 0.0) || !std::isfinite(delta)) delta = 1.0;
  double alpha = 0.0;
  summary.end = DenseSolveSummary::End::kNoConvergence;
  summary.message = "the maximum number of evaluations was reached";
  NormalEquations trial;
  bool done = false;
  while (!done) {
    ScalingVector(x, g, lower, upper, &v, &dv);
    if (g.cwiseProduct(v).lpNorm<Eigen::Infinity>() < options.gradient_tolerance) {
      summary.end = DenseSolveSummary::End::kConvergence;
      summary.message = "the scaled gradient is below gradient_tolerance";
      break;
    }
    const auto step_start = SteadyClock::now();
    // Coleman-Li's scaling applied in the unknowns scaled by the columns' norms.
    for (int i = 0; i < n; ++i) {
      if (dv[i] != 0.0) v[i] *= scale_inv[i];
    }
    const VectorXd d = v.cwiseSqrt().cwiseQuotient(scale_inv);
    const VectorXd diag_h = g.cwiseProduct(dv).cwiseQuotient(scale_inv);
    const VectorXd g_h = d.cwiseProduct(g);
    // H = D J'J D + diag(diag_h), the normal matrix of [J D; diag(sqrt(diag_h))].
    MatrixXd h = d.asDiagonal() * at.normal * d.asDiagonal();
    h.diagonal() += diag_h;
    const Eigen::SelfAdjointEigenSolver<MatrixXd> eigen(h);
    const VectorXd vg = eigen.eigenvectors().transpose() * g_h;
    const ScaledModel scaled{h, g_h};
    const double theta = std::max(0.995, 1.0 - g.cwiseProduct(v).lpNorm<Eigen::Infinity>());
    summary.step_seconds += SecondsSince(step_start);
    // Trial points until one lowers the cost (or a tolerance or limit ends the solve).
    for (;;) {
      if (summary.evaluations >= options.max_evaluations) {
        done = true;
        break;
      }
      if (SecondsSince(begin) > options.max_time_seconds) {
        summary.message = "the time limit was reached";
        done = true;
        break;
      }
      const auto select_start = SteadyClock::now();
      const VectorXd p_h =
          TrustRegionStep(eigen.eigenvalues(), eigen.eigenvectors(), vg, m, delta, &alpha);
      const Step step = SelectStep(x, scaled, p_h, d, delta, lower, upper, theta);
      const VectorXd x_new = StrictlyFeasible(x + step.x, lower, upper, 0.0);
      summary.step_seconds += SecondsSince(select_start);
      const double step_h_norm = step.h.norm();
      bool accepted = false;
      if (!evaluate(x_new, &trial)) {
        ++summary.rejected;
        delta = 0.25 * step_h_norm;
      } else {
        const double actual = cost - trial.cost;
        double ratio = 0.0;
        if (step.predicted > 0.0) {
          ratio = actual / step.predicted;
        } else if (step.predicted == 0.0 && actual == 0.0) {
          ratio = 1.0;
        }
        double next_delta = delta;
        if (ratio < 0.25) {
          next_delta = 0.25 * step_h_norm;
        } else if (ratio > 0.75 && step_h_norm > 0.95 * delta) {
          next_delta = 2.0 * delta;
        }
        const bool f_converged = actual < options.function_tolerance * cost && ratio > 0.25;
        const bool x_converged = (x_new - x).norm() < options.parameter_tolerance *
                                                          (options.parameter_tolerance + x.norm());
        accepted = actual > 0.0;
        if (accepted) {
          x = x_new;
          cost = trial.cost;
          std::swap(at, trial);
          g = at.gradient;
          update_scale(false);
          ++summary.accepted;
        } else {
          ++summary.rejected;
        }
        if (f_converged || x_converged) {
          summary.end = DenseSolveSummary::End::kConvergence;
          summary.message = f_converged ? "the cost changed by less than function_tolerance"
                                        : "the step is below parameter_tolerance";
          done = true;
        }
        if (next_delta > 0.0) alpha *= delta / next_delta;
        delta = next_delta;
      }
      if (callback) {
        const int answer = callback(summary.evaluations - 1, accepted, cost, x);
        if (answer != 0) {
          summary.end = answer > 0 ? DenseSolveSummary::End::kUserSuccess
                                   : DenseSolveSummary::End::kUserFailure;
          summary.message = "stopped by a callback";
          done = true;
        }
      }
      if (done || accepted) break;
      if (!(delta > 0.0)) {
        summary.end = DenseSolveSummary::End::kConvergence;
        summary.message = "the trust region shrank to nothing";
        done = true;
        break;
      }
    }
  }
  summary.final_cost = cost;
  *x_io = x;
  summary.total_seconds = SecondsSince(begin);
  return summary;
}

}  // namespace vesselid

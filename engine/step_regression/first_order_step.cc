#include "engine/step_regression/first_order_step.h"

#include <algorithm>
#include <cmath>

#include "engine/base/check.h"

namespace vesselid {
namespace {

// Sum of squared residuals of the step response with time constant exp(log_t).
struct StepCost {
  const std::vector<double>* tau;  // t_k - t_step
  const std::vector<double>* dy;   // y_k - y_before
  double change;                   // y_after - y_before

  double operator()(double log_t) const {
    const double rate = std::exp(-log_t);
    double cost = 0.0;
    for (size_t k = 0; k < tau->size(); ++k) {
      const double r = (*dy)[k] - change * -std::expm1(-(*tau)[k] * rate);
      cost += r * r;
    }
    return cost;
  }
};

}  // namespace

bool FirstOrderStepOptions::IsValid(std::string* error) const {
  if (!(std::isfinite(min_time_constant) && min_time_constant > 0.0)) {
    *error = "min_time_constant must be finite and > 0";
  } else if (!(std::isfinite(max_time_constant) && max_time_constant > min_time_constant)) {
    *error = "max_time_constant must be finite and > min_time_constant";
  } else if (grid < 2) {
    *error = "grid must be >= 2";
  } else {
    return true;
  }
  return false;
}

bool FitFirstOrderStep(const std::vector<double>& t, const std::vector<double>& y, double t_step,
                       double y_before, double y_after, double input_change,
                       const FirstOrderStepOptions& options, FirstOrderStepFit* fit,
                       std::string* error) {
  VESSELID_CHECK(fit != nullptr && error != nullptr);
  *fit = FirstOrderStepFit();
  if (!options.IsValid(error)) {
    *error = "first-order step options: " + *error;
    return false;
  }
  if (t.size() != y.size()) {
    *error = "first-order step: " + std::to_string(t.size()) + " times but " +
             std::to_string(y.size()) + " samples";
    return false;
  }
  if (!std::isfinite(t_step) || !std::isfinite(y_before) || !std::isfinite(y_after) ||
      !std::isfinite(input_change)) {
    *error = "first-order step: t_step, y_before, y_after and input_change must be finite";
    return false;
  }
  const double change = y_after - y_before;
  if (!std::isfinite(change) || change == 0.0) {
    *error = "first-order step: the response change y_after - y_before is zero or not finite";
    return false;
  }
  if (input_change == 0.0) {
    *error = "first-order step: the input change is zero";
    return false;
  }
  std::vector<double> tau, dy;
  for (size_t k = 0; k < t.size(); ++k) {
    if (!std::isfinite(t[k])) {
      *error = "first-order step: time " + std::to_string(k) + " is not finite";
      return false;
    }
    if (std::isinf(y[k])) {
      *error = "first-order step: sample " + std::to_string(k) + " is infinite";
      return false;
    }
    if (t[k] < t_step || std::isnan(y[k])) continue;
    tau.push_back(t[k] - t_step);
    dy.push_back(y[k] - y_before);
  }
  if (tau.size() < 3) {
    *error = "first-order step: " + std::to_string(tau.size()) +
             " usable samples at or after the step (need >= 3)";
    return false;
  }

  const StepCost cost{&tau, &dy, change};
  const double log_min = std::log(options.min_time_constant);
  const double log_max = std::log(options.max_time_constant);
  const double step = (log_max - log_min) / (options.grid - 1);
  auto grid_point = [&](int i) { return i == options.grid - 1 ? log_max : log_min + i * step; };

  int best = 0;
  double best_cost = cost(log_min);
  for (int i = 1; i < options.grid; ++i) {
    const double c = cost(grid_point(i));
    if (c < best_cost) {
      best = i;
      best_cost = c;
    }
  }
  double best_log = grid_point(best);

  // Golden-section search on log T between the best grid point's neighbours.
  double a = grid_point(best > 0 ? best - 1 : 0);
  double b = grid_point(best < options.grid - 1 ? best + 1 : options.grid - 1);
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
  double c1 = cost(x1), c2 = cost(x2);
  for (int iteration = 0; iteration < 200 && b - a > 1e-13; ++iteration) {
    if (c1 <= c2) {
      b = x2;
      x2 = x1;
      c2 = c1;
      x1 = b - ratio * (b - a);
      c1 = cost(x1);
    } else {
      a = x1;
      x1 = x2;
      c1 = c2;
      x2 = a + ratio * (b - a);
      c2 = cost(x2);
    }
  }
  const double refined_log = c1 <= c2 ? x1 : x2;
  const double refined_cost = std::min(c1, c2);
  if (refined_cost < best_cost) {  // else a grid point (e.g. a range end) is still the best
    best_log = refined_log;
    best_cost = refined_cost;
  }

  fit->at_bound = best_log == log_min || best_log == log_max;
  fit->time_constant = best_log == log_min   ? options.min_time_constant
                       : best_log == log_max ? options.max_time_constant
                                             : std::exp(best_log);
  fit->gain = input_change / change;
  fit->inertia = fit->gain * fit->time_constant;
  fit->samples = static_cast<int>(tau.size());
  fit->rms = std::sqrt(best_cost / fit->samples);
  return true;
}

}  // namespace vesselid

#include "engine/solve/search_box.h"

#include <algorithm>
#include <cmath>

namespace vesselid {

SearchBox::SearchBox(const OutputErrorProblem& problem) {
  const std::vector<Variable>& variables = problem.variables();
  const ModelInfo& info = problem.model().info();
  for (size_t i = 0; i < variables.size(); ++i) {
    const Variable& v = variables[i];
    if (!v.free || v.kind != Variable::Kind::kParameter || !(v.upper > v.lower)) continue;
    double lower = v.lower, upper = v.upper;
    bool log = false;
    if (v.bounded()) {
      // A positive parameter bounded below by 0 is searched over the top decades of its box.
      const bool positive = info.ParameterPositive(v.index) && v.lower == 0.0 && v.upper > 0.0;
      if (positive) lower = kPositiveFloor * v.upper;
      log = positive || v.lower > 0.0 || v.upper < 0.0;
    } else {
      // Around the start, cut to the bound it has.
      const double start = v.value();
      const bool positive = start > 0.0 && (v.lower >= 0.0 || info.ParameterPositive(v.index));
      const bool negative = start < 0.0 && v.upper <= 0.0;
      if (positive || negative) {
        lower = std::max(v.lower, positive ? start / kOpenSearchFactor : start * kOpenSearchFactor);
        upper = std::min(v.upper, positive ? start * kOpenSearchFactor : start / kOpenSearchFactor);
        log = true;
      } else {
        const double span = kOpenSearchFactor * std::abs(v.scale);
        lower = std::max(v.lower, start - span);
        upper = std::min(v.upper, start + span);
      }
      if (!(upper > lower) || !std::isfinite(lower) || !std::isfinite(upper)) continue;
    }
    searched_.push_back(static_cast<int>(i));
    names_.push_back(v.name);
    lower_.push_back(lower);
    upper_.push_back(upper);
    log_.push_back(log);
    around_start_.push_back(!v.bounded());
  }
  // Shared parameters only: per-experiment copies are separate unknowns.
  for (const auto& [first, second] : info.exchangeable) {
    int a = -1, b = -1;
    for (int k = 0; k < dimension(); ++k) {
      const Variable& v = variables[searched_[k]];
      if (v.experiment >= 0) continue;
      if (v.index == first) a = k;
      if (v.index == second) b = k;
    }
    if (a >= 0 && b >= 0) pairs_.emplace_back(a, b);
  }
}

std::vector<double> SearchBox::Values(const std::vector<double>& z,
                                      const std::vector<double>& base) const {
  std::vector<double> values = base;
  std::vector<double> theta(dimension());
  for (int k = 0; k < dimension(); ++k) {
    const double u = std::clamp(z[k], 0.0, 1.0);
    if (log_[k]) {
      const double sign = lower_[k] > 0.0 ? 1.0 : -1.0;
      const double lo = std::abs(lower_[k]), hi = std::abs(upper_[k]);
      // Negative box: |theta| runs from |u| (z = 0) to |l|, so z = 0 is still the lower bound.
      theta[k] = sign > 0 ? lo * std::pow(hi / lo, u) : -hi * std::pow(lo / hi, 1.0 - u);
    } else {
      theta[k] = lower_[k] + u * (upper_[k] - lower_[k]);
    }
  }
  // Ordered half: swap a pair drawn the wrong way round if each value fits the other's bounds.
  for (const auto& [a, b] : pairs_) {
    if (theta[a] >= theta[b]) continue;
    if (theta[b] <= upper_[a] && theta[b] >= lower_[a] && theta[a] <= upper_[b] &&
        theta[a] >= lower_[b]) {
      std::swap(theta[a], theta[b]);
    }
  }
  for (int k = 0; k < dimension(); ++k) values[searched_[k]] = theta[k];
  return values;
}

std::vector<double> SearchBox::Coordinates(const std::vector<double>& values) const {
  std::vector<double> z(dimension());
  for (int k = 0; k < dimension(); ++k) {
    const double t = std::clamp(values[searched_[k]], lower_[k], upper_[k]);
    if (log_[k]) {
      z[k] = lower_[k] > 0.0 ? std::log(t / lower_[k]) / std::log(upper_[k] / lower_[k])
                             : 1.0 - std::log(t / upper_[k]) / std::log(lower_[k] / upper_[k]);
    } else {
      z[k] = (t - lower_[k]) / (upper_[k] - lower_[k]);
    }
  }
  return z;
}

double SearchBox::Distance(const std::vector<double>& a, const std::vector<double>& b) const {
  // Both in the ordered half: a solve may end with an exchangeable pair either way round.
  const std::vector<double> za = Coordinates(Values(Coordinates(a), a));
  const std::vector<double> zb = Coordinates(Values(Coordinates(b), b));
  double distance = 0.0;
  for (int k = 0; k < dimension(); ++k) distance = std::max(distance, std::abs(za[k] - zb[k]));
  return distance;
}

}  // namespace vesselid

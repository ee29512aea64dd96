// The box a global start searches, as the unit cube [0, 1]^n. A variable whose bounds share
// a strict sign (0 < l < u, or l < u < 0: time constants, masses, gains of known sign) is
// searched in log coordinates, the rest linearly:
//
//   log:     theta = sign l * |l| (|u| / |l|)^z        linear: theta = l + z (u - l)
//
// so that a time constant is as likely to be drawn in [0.1, 1] as in [1, 10]. A parameter the
// model declares positive (ModelInfo::positive_parameters) with a lower bound 0 is searched
// in log coordinates over [kPositiveFloor u, u] (its solves may still go below). Exchangeable
// parameter pairs (the model is symmetric in them, ModelInfo::exchangeable) are folded into
// the ordered half first >= second: the other half holds the same simulations again.
//
// A parameter with a one-sided bound or none is searched around its start s (its value when
// the box is made), cut to the bounds it has: in log coordinates over [s / F, s F] when its
// sign is fixed (a bound at 0 or beyond on the other side, or the model declares it positive),
// else linearly over s +- F scale (Variable::scale: |start|, or as configured), F =
// kOpenSearchFactor. A parameter with no bounds and a start of 0 and scale 1 is still searched
// (over [-F, F]); give it a scale or bounds to say its size. The solves keep the parameter's
// own bounds: the box only places the points.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/solve/output_error_problem.h"

namespace vesselid {

constexpr double kPositiveFloor = 1e-3;
constexpr double kOpenSearchFactor = 3.0;

class SearchBox {
 public:
  // The free, bounded model parameters of `problem` (initial states and input corrections
  // keep their current values; they follow the parameters in each solve).
  explicit SearchBox(const OutputErrorProblem& problem);

  int dimension() const { return static_cast<int>(searched_.size()); }
  const std::vector<std::string>& names() const { return names_; }
  bool logarithmic(int k) const { return log_[k]; }
  // Whether coordinate k's range comes from its start (a one-sided or missing bound).
  bool around_start(int k) const { return around_start_[k]; }
  double lower(int k) const { return lower_[k]; }
  double upper(int k) const { return upper_[k]; }
  // Searched coordinates (indices into dimension()) of each exchangeable pair.
  const std::vector<std::pair<int, int>>& exchangeable() const { return pairs_; }

  // Full value vector (as OutputErrorProblem::Values) for the point z of the cube; the
  // unsearched variables take their values from `base`. Exchangeable pairs are ordered.
  std::vector<double> Values(const std::vector<double>& z, const std::vector<double>& base) const;
  // The cube coordinates of a value vector (values outside the bounds are clamped).
  std::vector<double> Coordinates(const std::vector<double>& values) const;
  // Max-norm distance of two value vectors in cube coordinates, exchangeable pairs ordered.
  double Distance(const std::vector<double>& a, const std::vector<double>& b) const;

 private:
  std::vector<int> searched_;  // variable indices
  std::vector<std::string> names_;
  std::vector<double> lower_, upper_;
  std::vector<bool> log_;
  std::vector<bool> around_start_;
  std::vector<std::pair<int, int>> pairs_;
};

}  // namespace vesselid

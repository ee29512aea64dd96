// What a filter-error stage reports of its disturbance model in results.json (and so to
// Python's RunResult.json): the model in words, the likelihood, auto's candidates with their
// BIC, and the held-out predictions through the filter beside the free run.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace vesselid {

// One candidate of `noise: {method: auto}` (disturbance_choice.h).
struct DisturbanceCandidateScore {
  std::string name;  // "output_error", "white", "ar1(psi)", "process(eta2)", ...
  bool solved = false;
  std::string why;  // why not solved
  double negative_log_likelihood = std::numeric_limits<double>::quiet_NaN();
  int unknowns = 0;
  double bic = std::numeric_limits<double>::quiet_NaN();  // 2 (-log L) + k log N
  bool chosen = false;
};

// A held-out experiment's output predicted through the filter (filter_prediction.h).
struct FilterPrediction {
  std::string experiment, output;
  int steps = 0;              // k, in sample nodes
  double seconds_ahead = 0.0;  // k times the run's mean node interval
  double k_step_fit_percent = std::numeric_limits<double>::quiet_NaN();  // NaN: run too short
  double one_step_fit_percent = std::numeric_limits<double>::quiet_NaN();
  // The stage's validation fit of the same output: its free run from the measured start, or
  // after the burn-in where the stage estimates the held-out run's states (held_out.h).
  double free_run_fit_percent = std::numeric_limits<double>::quiet_NaN();
};

struct DisturbanceReport {
  std::string method;  // "" (output error), "filter_error" or "auto"
  std::string model;   // in words, as the disturbance_model finding gives it
  bool filter_error = false;  // the stage's fit is the filter's (auto may keep output error)
  double negative_log_likelihood = std::numeric_limits<double>::quiet_NaN();
  std::vector<DisturbanceCandidateScore> candidates;  // `auto` only, output error first
  std::vector<FilterPrediction> predictions;          // the stage's held-out experiments

  bool active() const { return !method.empty(); }
};

}  // namespace vesselid

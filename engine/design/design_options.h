// What `vesselid design` is asked (the config's `design:` section, design_config.h): the next
// experiment's duration and sampling, the family and limits of each input, the criterion, the
// box the track must stay in and how hard to search.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vesselid {

// How one model input is planned.
//   steps:     piecewise-constant levels on a grid of `hold` s, each in [lower, upper];
//   multisine: value + sum_k a_k sin(2 pi t / T_k + phi_k) over `periods`, amplitudes and
//              phases free;
//   zigzag:    the rudder at +-a, reversed when the heading change passes +-psi_z (closed loop
//              on the heading output `psi`), a in [0, max(|lower|, |upper|)] and psi_z within
//              `headings`;
//   fixed:     held at `value`.
// Every family's command then passes the actuator: clipped to [lower, upper] and followed at
// no more than `rate` per second (0: at once), so that every planned input meets its limits.
struct DesignInput {
  enum class Family { kSteps, kMultisine, kZigzag, kFixed };
  std::string name;  // model input
  Family family = Family::kFixed;
  double lower = 0.0, upper = 0.0;  // model units
  double rate = 0.0;                // model units per s; 0: no limit
  double value = 0.0;               // the input when not excited (fixed: always), model units
  double hold = 0.0;                // steps: s per level (0: duration / 12)
  std::vector<double> periods;      // multisine, s (empty: duration / {1, 2, 3, 5, 8, 13})
  std::pair<double, double> headings = {0.0, 0.0};  // zigzag: psi_z range, rad (config: deg)
  // The values in the config and the planned CSV are in degrees (the model's are radians).
  bool degrees = false;
};

enum class DesignCriterion {
  kD,          // maximise log det of the information (of the relative parameters p / |p|)
  kA,          // minimise the trace of the relative covariance, sum (se_i / |p_i|)^2
  kE,          // maximise the smallest eigenvalue of the relative information
  kParameter,  // minimise one parameter's variance ("shrink T3")
};

struct DesignOptions {
  std::string family;  // the config's model family (checked against the run's), or empty
  // s; <= 0: the time the current model takes for a 20/20 zigzag of four rudder reversals.
  double duration = 0.0;
  double sample_time = 0.0;  // s, of the planned log (required)
  std::vector<DesignInput> inputs;
  DesignCriterion criterion = DesignCriterion::kD;
  std::string parameter;  // kParameter: its name
  // Output -> [lower, upper] the predicted track must stay within, relative to where the
  // experiment starts (positions n, e of a model that has them).
  std::map<std::string, std::pair<double, double>> box;
  // Output -> standard deviation of its measurement noise in the planned log (model units);
  // absent: the residual RMS of the run's final fit of that output.
  std::map<std::string, double> noise;
  // Initial state of the planned experiment (model units); absent states: 0.
  std::map<std::string, double> initial_state;
  // > 0: the plan starts from the state the current model reaches after this many s at the
  // inputs' values from initial_state (a craft already under way).
  double settle = 0.0;
  // States estimated from the planned record (its nuisance): default the run's last stage's
  // free initial states.
  std::vector<std::string> free_initial_states;
  bool free_initial_states_given = false;
  int starts = 24;             // random starts of the search (steps, multisine)
  int max_evaluations = 1500;  // of the local search from the best starts
  int refined = 3;             // starts refined locally
  unsigned seed = 1;
  // > 0: the criterion averaged over this many members of the run's ensemble (robust to the
  // estimate being wrong); the spread of each plan's standard errors is reported.
  int ensemble_members = 0;
  int threads = 0;  // 0: the machine's cores
};

}  // namespace vesselid

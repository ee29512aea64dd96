// What `vesselid study` runs, as the config's `study` section describes it:
//
//   study:
//     seed: 1          # every case's random numbers derive from it and the case index
//     threads: 0       # worker threads per process; 0: cores / processes on the machine
//     profile:     {stage | stages, parameters, points, span, confidence}
//     monte_carlo: {stage, runs, noise, truth (| estimate), start, confidence}
//     starts:      {stage, runs, sampling, global, tolerance}
//     partitions:  {stage, experiments, repetitions, validation_share, training_shares,
//                   methods}
//
// Each part studies one output-error stage of the run, the last one when `stage` is not
// given, with the parameters the run carries into it. Partitions studies a least-squares or
// an output-error stage (partition_study.h); without `stage`, the run's last stage when it is
// an output-error one, else its first least-squares stage. Its `experiments` are the pool of
// a least-squares stage (default: the stage's experiments and validation experiments) and
// are added to an output-error stage's own experiments.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/solve/global_start.h"
#include "engine/study/case_options.h"
#include "engine/study/partition_options.h"

namespace vesselid {

// Profile likelihood: each listed parameter held on a grid while the others are re-estimated;
// the confidence interval is where 2 (F(theta_j) - F^) / s^2 stays below chi2_1(confidence).
struct ProfileOptions {
  std::vector<std::string> stages;     // each profiled in turn; empty: the run's last one
  std::vector<std::string> parameters;  // empty: every free parameter of the stage
  int points = 21;                      // grid points per parameter (odd: one at the optimum)
  double span = 4.0;                    // grid half-width in standard errors (bounds if none)
  double confidence = 0.95;
};

// Monte Carlo noise study: the stage's experiments simulated with `truth`, Gaussian noise of
// `noise` (per model output, in its units) added to every sample and (per model input) to
// every sample of the input's recorded column, identified `runs` times.
struct MonteCarloOptions {
  std::string stage;
  int runs = 200;
  // Output or input -> standard deviation. An output not named takes the residual SD of the
  // stage's fit with `truth: estimate`; without it every compared output must be named.
  std::map<std::string, double> noise;
  std::map<std::string, double> truth;  // parameter -> value (default: simulation.truth)
  // truth: estimate - a parametric bootstrap: the stage is solved on the data first and its
  // estimate (parameters, per-experiment values, initial states) is the truth.
  bool truth_estimate = false;
  std::string truth_where;  // "file:line: study.monte_carlo.truth", for messages of the solve
  // start: truth - a local solve from the truth (no global start: the noise alone is
  // measured); start: stage (default) - the stage as configured, from its starts.
  bool start_at_truth = false;
  double confidence = 0.95;             // of the intervals whose coverage is counted
};

// Start-point study: `runs` starts drawn in the bounds of the free parameters, each solved
// locally only and with the global start first.
struct StartPointOptions {
  std::string stage;
  int runs = 50;
  bool log_sampling = false;      // sampling: log (positive bounds) or uniform
  // > 0: each start log-uniform in [o / spread, o * spread] (o: the run's optimum of the
  // parameter, sign kept), cut to the bounds; 0: drawn in the whole bounds.
  double spread = 0.0;
  GlobalStartOptions global;      // the stage's own global options unless given
  bool global_given = false;
  // Two optima are the same when every free parameter agrees within tolerance * max(|value|,
  // its scale); a start "reaches the best" when its optimum is the lowest-cost one.
  double tolerance = 1e-3;
};

struct StudyConfig {
  unsigned seed = 1;
  CaseOptions execution;
  std::optional<ProfileOptions> profile;
  std::optional<MonteCarloOptions> monte_carlo;
  std::optional<StartPointOptions> starts;
  std::optional<StudyOptions> partitions;
};

}  // namespace vesselid

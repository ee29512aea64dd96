// Fit of simulated to measured outputs, per experiment and channel (e = y_sim - y_meas; an
// angle is compared unwrapped unless the experiment wraps it, Experiment::Wrapped):
//   RMSE = sqrt(mean e^2), MAE = mean |e|, R^2 = 1 - SSE/SST,
//   fit % (NRMSE) = 100 (1 - ||e|| / ||y - mean y||),
//   for a wrapped angle both taken modulo one turn: e wrapped to (-pi, pi] and y - mean y
//   as wrap(y - circular mean of y), so that a spread of many turns (degrees read as
//   radians) cannot make a wrapped residual look small,
//   rms_cost (seed 002) = sqrt(mean e^2) over all compared samples of the experiment.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "engine/data/noise_level.h"
#include "engine/data/trajectory.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

struct ChannelMetrics {
  std::string experiment;
  std::string output;
  int samples = 0;
  double rmse = 0.0, mae = 0.0, r2 = 0.0, fit_percent = 0.0;
  // MAE of the plainest prediction, holding the first measured value: a simulation worse
  // than it predicts nothing.
  double hold_mae = std::numeric_limits<double>::quiet_NaN();
  // Noise level of the measurement from the data alone (noise_level.h): a fit whose RMSE is
  // many times it has missed the signal, not the noise.
  double noise = std::numeric_limits<double>::quiet_NaN();
};

// A channel whose simulation has missed its record, judged against what the record allows:
// the record varies beyond its noise (its SD, sqrt(RMSE^2 / (1 - R2)), above
// kSignalToNoise x its noise level; a flat record can be fitted by nothing better than its
// mean), and the simulation predicts it worse than its mean (R2 < 0) or worse than holding its
// first value (MAE above hold MAE). Not an RMSE against the noise level: smooth model-test
// records have a tiny noise level and any real fit would fail that.
inline constexpr double kSignalToNoise = 3.0;
inline double ChannelSignalSd(const ChannelMetrics& m) {
  return m.r2 < 1.0 ? m.rmse / std::sqrt(1.0 - m.r2) : std::numeric_limits<double>::infinity();
}
inline bool ChannelVaries(const ChannelMetrics& m) {
  return !(std::isfinite(m.noise) && m.noise > 0.0) || ChannelSignalSd(m) > kSignalToNoise * m.noise;
}
inline bool FitFailed(const ChannelMetrics& m) {
  return ChannelVaries(m) && (m.r2 < 0.0 || (std::isfinite(m.hold_mae) && m.mae > m.hold_mae));
}
// A fit that did not fail but explains less than half of a varying record: fit % below
// kPoorFitPercent (RMSE above half the record's SD).
inline constexpr double kPoorFitPercent = 50.0;
inline bool FitPoor(const ChannelMetrics& m) {
  return !FitFailed(m) && ChannelVaries(m) && std::isfinite(m.fit_percent) &&
         m.fit_percent < kPoorFitPercent;
}

// Metrics of a regression's fit to its samples (no MAE or fit %: only RMS residual and R2).
inline ChannelMetrics RegressionMetrics(const std::string& experiment, const std::string& output,
                                        int samples, double rms, double r2) {
  const double unknown = std::numeric_limits<double>::quiet_NaN();
  return {experiment, output, samples, rms, unknown, r2, unknown, unknown, unknown};
}

// Accumulates the errors e = simulated - measured of one channel into ChannelMetrics.
class MetricAccumulator {
 public:
  void Add(double simulated, double measured, bool angle = false);
  ChannelMetrics Finish(const std::string& experiment, const std::string& output) const;
  int samples() const { return n_; }
  double sse() const { return sse_; }

 private:
  int n_ = 0;
  double sse_ = 0.0, sae_ = 0.0, sum_ = 0.0, sum2_ = 0.0, hold_sae_ = 0.0, first_ = 0.0;
  std::vector<double> angles_;  // measured values of a wrapped angle (its spread, see above)
  NoiseLevel noise_;
};

// A measured initial state of a held-out run whose start was refitted, against its measurement:
// `sds` noise SDs of the output apart.
struct StartOffset {
  std::string state;
  double measured = 0.0, refitted = 0.0, noise = 0.0, sds = 0.0;
};

// How a held-out run was started and what of it was scored (empty mode: a training fit).
//   measured: measured states start at their measurement; the unmeasured ones listed free and
//     the run's own parameters are estimated on the first `burn_in` s, which are not scored.
//   refitted: every listed state (and the run's own parameters) estimated on the whole run,
//     which is scored whole; `measured_start` holds the figures from the measured start
//     (burn-in as above) and `offsets` the refitted measured states.
struct HeldOutStartReport {
  std::string mode;
  double burn_in = 0.0;  // s not scored (measured start); 0: none
  double requested_burn_in = 0.0;  // the configured burn_in (0: the default)
  std::vector<std::string> estimated;  // states and parameters estimated on the burn-in
  // Per-run parameters whose burn-in estimate was weighed against the training runs' spread.
  std::vector<std::string> weighed;
  // With refitted starts: what was estimated on the whole run (states and parameters).
  std::vector<std::string> refitted;
  std::vector<ChannelMetrics> measured_start;
  bool measured_start_diverged = false;
  std::vector<StartOffset> offsets;
  double implausible_sds = 0.0;  // an offset beyond this many noise SDs is a finding
  // From the measured start: the initial state the run was flown from (model state order)
  // and the parameter values, its own per-experiment ones included (model order).
  std::vector<double> initial_state;
  std::vector<double> values;
};

// Whether a held-out run's prediction error is what the fit leads one to expect
// (prediction_band.h): the error left after the best adjustment of the parameters and the
// initial state within their uncertainty,
//   Q = min_d  sum_i (r_i - s_i d)^2 / sigma_o(i)^2 + d' P^-1 d,
// over the scored samples, with sigma_o^2 the training fit's mean square residual of output o
// and P the covariance of the estimates and of the start. A prediction as good as the fit
// gives Q / samples near 1.
struct PredictionBand {
  bool done = false;
  int samples = 0;
  double ratio = 0.0;      // Q / samples
  double raw_ratio = 0.0;  // sum r^2 / sigma^2 / samples: before the adjustment
  std::vector<std::string> outputs;
  std::vector<double> output_ratio;  // per output: its raw ratio
};

struct ExperimentFit {
  std::string experiment;
  // The simulation diverged (or its initial states could not be estimated): no metrics, the
  // reason in `message` ("diverges after t = 12.3 s"), the trace up to where it got.
  bool diverged = false;
  std::string message;
  double rms_cost = 0.0;
  std::vector<ChannelMetrics> channels;
  Trajectory trace;  // t, <output>_measured, <output>_simulated per compared output
  HeldOutStartReport start;  // held-out runs: how the run was started and scored
  PredictionBand band;       // held-out runs of the final validation, from the measured start
};

// Time of the last node a simulation reached (its outputs are finite), from the outputs
// SimulateOutputs left: NaN from the node where it stopped on.
double DivergenceTime(const Experiment& experiment, const std::vector<double>& outputs,
                      int num_outputs);

// "simulation of experiment 'run2' diverges after t = 12.3 s".
std::string DivergenceMessage(const Experiment& experiment, const std::vector<double>& outputs,
                              int num_outputs);

// Simulates every experiment at the problem's current values; one that diverges is recorded
// as such (ExperimentFit::diverged). False (with `error` naming it) if any diverged. Samples
// at or before `scored_from` (the end of a held-out run's burn-in) are traced, not scored.
bool EvaluateFit(const OutputErrorProblem& problem, std::vector<ExperimentFit>* fits,
                 std::string* error,
                 double scored_from = -std::numeric_limits<double>::infinity());

}  // namespace vesselid

// Fit of simulated to measured outputs, per experiment and channel (e = y_sim - y_meas,
// angle channels wrapped):
//   RMSE = sqrt(mean e^2), MAE = mean |e|, R^2 = 1 - SSE/SST,
//   fit % (NRMSE) = 100 (1 - ||e|| / ||y - mean y||),
//   rms_cost (seed 002) = sqrt(mean e^2) over all compared samples of the experiment.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

struct ChannelMetrics {
  std::string experiment;
  std::string output;
  int samples = 0;
  double rmse = 0.0, mae = 0.0, r2 = 0.0, fit_percent = 0.0;
};

// Metrics of a regression's fit to its samples (no MAE or fit %: only RMS residual and R2).
inline ChannelMetrics RegressionMetrics(const std::string& experiment, const std::string& output,
                                        int samples, double rms, double r2) {
  const double unknown = std::numeric_limits<double>::quiet_NaN();
  return {experiment, output, samples, rms, unknown, r2, unknown};
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
  double sse_ = 0.0, sae_ = 0.0, sum_ = 0.0, sum2_ = 0.0;
};

struct ExperimentFit {
  std::string experiment;
  double rms_cost = 0.0;
  std::vector<ChannelMetrics> channels;
  Trajectory trace;  // t, <output>_measured, <output>_simulated per compared output
};

// Simulates every experiment at the problem's current values. False if one diverges.
bool EvaluateFit(const OutputErrorProblem& problem, std::vector<ExperimentFit>* fits,
                 std::string* error);

}  // namespace vesselid

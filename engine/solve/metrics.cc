#include "engine/solve/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/base/angle.h"

namespace vesselid {

void MetricAccumulator::Add(double simulated, double measured, bool angle) {
  double residual = simulated - measured;
  if (angle) residual = WrapAngle(residual);
  if (n_ == 0) first_ = measured;
  if (angle) angles_.push_back(measured);
  if (angle) {
    noise_.Add(measured, [](double d) { return WrapAngle(d); });
  } else {
    noise_.Add(measured);
  }
  hold_sae_ += std::abs(angle ? WrapAngle(measured - first_) : measured - first_);
  ++n_;
  sse_ += residual * residual;
  sae_ += std::abs(residual);
  sum_ += measured;
  sum2_ += measured * measured;
}

ChannelMetrics MetricAccumulator::Finish(const std::string& experiment,
                                         const std::string& output) const {
  const double kNaN = std::numeric_limits<double>::quiet_NaN();
  ChannelMetrics m;
  m.experiment = experiment;
  m.output = output;
  m.samples = n_;
  if (n_ == 0) return m;
  m.rmse = std::sqrt(sse_ / n_);
  m.mae = sae_ / n_;
  m.hold_mae = hold_sae_ / n_;
  m.noise = noise_.Sigma();
  double sst = std::max(0.0, sum2_ - sum_ * sum_ / n_);
  if (!angles_.empty()) {
    double sin_sum = 0.0, cos_sum = 0.0;
    for (double a : angles_) {
      sin_sum += std::sin(a);
      cos_sum += std::cos(a);
    }
    const double mean = std::atan2(sin_sum, cos_sum);
    sst = 0.0;
    for (double a : angles_) sst += WrapAngle(a - mean) * WrapAngle(a - mean);
  }
  m.r2 = sst > 0 ? 1.0 - sse_ / sst : kNaN;
  m.fit_percent = sst > 0 ? 100.0 * (1.0 - std::sqrt(sse_ / sst)) : kNaN;
  return m;
}

double DivergenceTime(const Experiment& experiment, const std::vector<double>& outputs,
                      int num_outputs) {
  double reached = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < experiment.num_nodes(); ++k) {
    const size_t first = static_cast<size_t>(k) * num_outputs;
    if (first >= outputs.size()) break;
    bool finite = true;
    for (int c = 0; c < num_outputs; ++c) finite &= std::isfinite(outputs[first + c]);
    if (!finite) break;
    reached = experiment.node_time[k];
  }
  return reached;
}

std::string DivergenceMessage(const Experiment& experiment, const std::vector<double>& outputs,
                              int num_outputs) {
  const double t = DivergenceTime(experiment, outputs, num_outputs);
  char text[64];
  if (std::isnan(t)) {
    std::snprintf(text, sizeof(text), "at its start (t = %g s)", experiment.node_time.front());
  } else {
    std::snprintf(text, sizeof(text), "after t = %g s", t);
  }
  return "simulation of experiment '" + experiment.name + "' diverges " + text;
}

bool EvaluateFit(const OutputErrorProblem& problem, std::vector<ExperimentFit>* fits,
                 std::string* error, double scored_from) {
  fits->clear();
  std::string first_divergence;
  const ModelInfo& info = problem.model().info();
  const int ny = static_cast<int>(info.outputs.size());
  const double kMissing = std::numeric_limits<double>::quiet_NaN();
  for (size_t e = 0; e < problem.experiments().size(); ++e) {
    const Experiment& experiment = problem.experiments()[e];
    std::vector<double> p = problem.ParametersOf(static_cast<int>(e));
    std::vector<double> x0 = problem.InitialStateOf(static_cast<int>(e));
    const std::vector<double> c = problem.InputCorrectionsOf(static_cast<int>(e));
    std::vector<double> outputs;
    ExperimentFit fit;
    fit.experiment = experiment.name;
    if (!problem.model().SimulateOutputs(experiment, p.data(), x0.data(), &outputs,
                                         c.empty() ? nullptr : c.data())) {
      fit.diverged = true;
      fit.message = DivergenceMessage(experiment, outputs, ny);
      if (first_divergence.empty()) first_divergence = fit.message;
    }
    fit.trace.t = experiment.node_time;
    std::vector<int> column_of(ny, -1);
    for (int c = 0; c < ny; ++c) {
      if (experiment.output_sample_count[c] == 0) continue;
      column_of[c] = static_cast<int>(fit.trace.names.size());
      fit.trace.names.push_back(info.outputs[c] + "_measured");
      fit.trace.names.push_back(info.outputs[c] + "_simulated");
      fit.trace.columns.emplace_back(experiment.num_nodes(), kMissing);
      fit.trace.columns.emplace_back(experiment.num_nodes(), kMissing);
    }
    std::vector<MetricAccumulator> channels(ny);
    for (int k = 0; k < experiment.num_nodes(); ++k) {
      for (int i = experiment.node_first_sample[k]; i < experiment.node_first_sample[k + 1]; ++i) {
        const ExperimentSample& s = experiment.samples[i];
        const double simulated = outputs[static_cast<size_t>(k) * ny + s.output];
        if (experiment.node_time[k] > scored_from)
          channels[s.output].Add(simulated, s.value, experiment.Wrapped(s.output));
        fit.trace.columns[column_of[s.output]][k] = s.value;
        fit.trace.columns[column_of[s.output] + 1][k] = simulated;
      }
    }
    double total_sse = 0.0;
    for (int c = 0; c < ny; ++c) {
      total_sse += channels[c].sse();
      if (channels[c].samples() == 0) continue;
      if (!fit.diverged)
        fit.channels.push_back(channels[c].Finish(experiment.name, info.outputs[c]));
    }
    int scored = 0;
    for (const MetricAccumulator& c : channels) scored += c.samples();
    fit.rms_cost = fit.diverged ? std::numeric_limits<double>::quiet_NaN()
                                : std::sqrt(total_sse / std::max(1, scored));
    fits->push_back(std::move(fit));
  }
  if (!first_divergence.empty()) *error = first_divergence;
  return first_divergence.empty();
}

}  // namespace vesselid

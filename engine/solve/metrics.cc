#include "engine/solve/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesselid {

void MetricAccumulator::Add(double simulated, double measured, bool angle) {
  double residual = simulated - measured;
  if (angle) residual = WrapAngle(residual);
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
  const double sst = std::max(0.0, sum2_ - sum_ * sum_ / n_);
  m.r2 = sst > 0 ? 1.0 - sse_ / sst : kNaN;
  m.fit_percent = sst > 0 ? 100.0 * (1.0 - std::sqrt(sse_ / sst)) : kNaN;
  return m;
}

bool EvaluateFit(const OutputErrorProblem& problem, std::vector<ExperimentFit>* fits,
                 std::string* error) {
  fits->clear();
  const ModelInfo& info = problem.model().info();
  const int ny = static_cast<int>(info.outputs.size());
  const double kMissing = std::numeric_limits<double>::quiet_NaN();
  for (size_t e = 0; e < problem.experiments().size(); ++e) {
    const Experiment& experiment = problem.experiments()[e];
    std::vector<double> p = problem.ParametersOf(static_cast<int>(e));
    std::vector<double> x0 = problem.InitialStateOf(static_cast<int>(e));
    std::vector<double> outputs;
    if (!problem.model().SimulateOutputs(experiment, p.data(), x0.data(), &outputs)) {
      *error = "simulation of experiment '" + experiment.name + "' diverges";
      return false;
    }
    ExperimentFit fit;
    fit.experiment = experiment.name;
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
        channels[s.output].Add(simulated, s.value, info.angle_outputs[s.output]);
        fit.trace.columns[column_of[s.output]][k] = s.value;
        fit.trace.columns[column_of[s.output] + 1][k] = simulated;
      }
    }
    double total_sse = 0.0;
    for (int c = 0; c < ny; ++c) {
      total_sse += channels[c].sse();
      if (channels[c].samples() == 0) continue;
      fit.channels.push_back(channels[c].Finish(experiment.name, info.outputs[c]));
    }
    fit.rms_cost = std::sqrt(total_sse / std::max(1, experiment.num_samples()));
    fits->push_back(std::move(fit));
  }
  return true;
}

}  // namespace vesselid

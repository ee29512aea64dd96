#include "engine/metrics.h"

#include <cmath>
#include <limits>

namespace vesselid {

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
    std::vector<double> sse(ny, 0.0), sae(ny, 0.0), sum(ny, 0.0), sum2(ny, 0.0);
    double total_sse = 0.0;
    for (int k = 0; k < experiment.num_nodes(); ++k) {
      for (int i = experiment.node_first_sample[k]; i < experiment.node_first_sample[k + 1]; ++i) {
        const ExperimentSample& s = experiment.samples[i];
        const double simulated = outputs[static_cast<size_t>(k) * ny + s.output];
        double residual = simulated - s.value;
        if (info.angle_outputs[s.output]) residual = WrapAngle(residual);
        sse[s.output] += residual * residual;
        sae[s.output] += std::abs(residual);
        sum[s.output] += s.value;
        sum2[s.output] += s.value * s.value;
        total_sse += residual * residual;
        fit.trace.columns[column_of[s.output]][k] = s.value;
        fit.trace.columns[column_of[s.output] + 1][k] = simulated;
      }
    }
    for (int c = 0; c < ny; ++c) {
      const int count = experiment.output_sample_count[c];
      if (count == 0) continue;
      ChannelMetrics m;
      m.experiment = experiment.name;
      m.output = info.outputs[c];
      m.samples = count;
      m.rmse = std::sqrt(sse[c] / count);
      m.mae = sae[c] / count;
      const double sst = std::max(0.0, sum2[c] - sum[c] * sum[c] / count);
      m.r2 = sst > 0 ? 1.0 - sse[c] / sst : std::numeric_limits<double>::quiet_NaN();
      m.fit_percent = sst > 0 ? 100.0 * (1.0 - std::sqrt(sse[c] / sst))
                              : std::numeric_limits<double>::quiet_NaN();
      fit.channels.push_back(m);
    }
    fit.rms_cost = std::sqrt(total_sse / std::max(1, experiment.num_samples()));
    fits->push_back(std::move(fit));
  }
  return true;
}

}  // namespace vesselid

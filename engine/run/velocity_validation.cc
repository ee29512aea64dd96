#include "engine/run/velocity_validation.h"

#include <cmath>

#include "engine/base/parallel_for.h"
#include "engine/run/integration_step.h"

namespace vesselid {

bool FreeRunMetrics(const RunConfig& config, const ModelHandle& model, const std::vector<double>& p,
                    const TrajectoryCache& cache, const VelocitySteps& steps,
                    std::vector<RegressionRecord>* records, std::vector<ChannelMetrics>* metrics,
                    std::vector<std::string>* diverged, std::string* error) {
  const ModelInfo& info = model.info();
  const RegressionForm& form = *model.regression_form();
  const int ny = static_cast<int>(info.outputs.size());
  std::vector<MetricAccumulator> accumulators(form.states.size());
  std::map<const Trajectory*, RecordChannels> record_channels;  // for the record's segments
  for (RegressionRecord& record : *records) {
    std::vector<Eigen::MatrixXd> phi;
    model.Regressors(p.data(), &record, &phi);  // internal states at p
    // The record's own window and grid: nodes at the grid output's samples.
    ExperimentSpec spec = *config.FindExperiment(record.record);
    spec.name = record.name;
    spec.segments = SegmentSelection();
    spec.t_begin = record.t.front();
    spec.t_end = record.t.back();
    ExperimentOptions options;
    options.outputs = {info.outputs[record.grid_output]};
    options.max_step =
        IntegrationStep(StepUse::kVelocityValidation, steps.configured, steps.stages, record.dt);
    Experiment experiment;
    const Trajectory& data = *cache.Find(record.record);
    RecordChannels& channels = record_channels.try_emplace(&data, data).first->second;
    if (!BuildExperiment(spec, &channels, info, options, &experiment, error)) {
      return false;
    }
    if (experiment.num_nodes() != record.size()) {
      *error = "experiment '" + record.name + "': simulation grid does not match the record";
      return false;
    }
    const Eigen::VectorXd x0 = record.x.row(0).transpose();
    std::vector<double> outputs;
    if (!model.SimulateOutputs(experiment, p.data(), x0.data(), &outputs)) {
      diverged->push_back("free run of " + DivergenceMessage(experiment, outputs, ny) +
                          "; left out of the free-run metrics");
      continue;
    }
    for (size_t i = 0; i < form.states.size(); ++i) {
      const int s = form.states[i];
      const int o = info.OutputIndex(info.states[s]);
      if (o < 0) continue;
      for (int k = 1; k < record.size(); ++k) {
        accumulators[i].Add(outputs[static_cast<size_t>(k) * ny + o], record.x(k, s));
      }
    }
  }
  for (size_t i = 0; i < form.states.size(); ++i) {
    if (accumulators[i].samples() == 0) continue;
    metrics->push_back(accumulators[i].Finish("free-run", info.states[form.states[i]]));
  }
  return true;
}

std::vector<double> WithOwnValues(const ModelInfo& info, const std::vector<double>& p,
                                  const HeldOutParameters* own, const std::string& record) {
  std::vector<double> values = p;
  if (own == nullptr || !own->fitted) return values;
  for (const Estimate& e : own->estimates) {
    if (e.experiment != record) continue;
    const int index = info.ParameterIndex(e.name.substr(0, e.name.find('[')));
    if (index >= 0 && std::isfinite(e.value)) values[index] = e.value;
  }
  return values;
}

bool ValidateVelocities(const RunConfig& config, const ModelHandle& model,
                        const std::vector<std::string>& names, const RegressionDataOptions& data,
                        const std::vector<double>& p, TrajectoryCache* cache,
                        const VelocitySteps& steps, std::vector<ChannelMetrics>* metrics,
                        std::vector<std::string>* diverged, std::string* error, int threads,
                        const HeldOutParameters* own) {
  metrics->clear();
  // The records are prepared in turn (preparing notes skipped segments in the cache), then
  // measured in parallel, each into its own slot, collected in the given order.
  const int count = static_cast<int>(names.size());
  std::vector<std::vector<RegressionRecord>> records(count);
  for (int i = 0; i < count; ++i) {
    if (!PrepareRegressionRecords(config, {names[i]}, model, data, cache, &records[i], error)) {
      return false;
    }
  }
  struct Measured {
    bool ok = false;
    std::string error;
    std::vector<ChannelMetrics> one_step, free_run;
    std::vector<std::string> diverged;
  };
  std::vector<Measured> measured(count);
  ParallelFor(count, threads, [&](int i) {
    Measured& m = measured[i];
    const std::vector<double> values = WithOwnValues(model.info(), p, own, names[i]);
    m.ok =
        OneStepMetrics(model, values, LeastSquaresOptions(), &records[i], "one-step", &m.one_step,
                       &m.error) &&
        FreeRunMetrics(config, model, values, *cache, steps, &records[i], &m.free_run,
                       &m.diverged, &m.error);
  });
  for (int i = 0; i < count; ++i) {
    Measured& m = measured[i];
    if (!m.ok) {
      *error = m.error;
      return false;
    }
    diverged->insert(diverged->end(), m.diverged.begin(), m.diverged.end());
    for (std::vector<ChannelMetrics>* part : {&m.one_step, &m.free_run}) {
      for (ChannelMetrics& c : *part) {
        c.experiment = names[i] + " " + c.experiment;
        metrics->push_back(std::move(c));
      }
    }
  }
  return true;
}

}  // namespace vesselid

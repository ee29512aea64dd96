#include "engine/run/fit_residuals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "engine/base/angle.h"

namespace vesselid {
namespace {

int Column(const Trajectory& trace, const std::string& name) {
  for (size_t c = 0; c < trace.names.size(); ++c) {
    if (trace.names[c] == name) return static_cast<int>(c);
  }
  return -1;
}

// The inputs the experiment feeds, `count` samples each (an unmapped optional input is NaN
// throughout and left out), moved from `inputs` into `names` and `fed`.
void FedInputs(const ModelInfo& info, size_t count, std::vector<std::vector<double>>* inputs,
               std::vector<std::string>* names, std::vector<std::vector<double>>* fed) {
  for (size_t i = 0; i < inputs->size() && i < info.inputs.size(); ++i) {
    std::vector<double>& input = (*inputs)[i];
    const bool finite =
        std::all_of(input.begin(), input.end(), [](double v) { return std::isfinite(v); });
    if (!finite || input.size() != count) continue;
    names->push_back(info.inputs[i]);
    fed->push_back(std::move(input));
  }
}

}  // namespace

NodeInputs::NodeInputs(const Experiment& experiment)
    : experiment_(experiment),
      num_inputs_(static_cast<size_t>(experiment.num_inputs)),
      cache_rows_(num_inputs_ > 0 ? experiment.input_cache.size() / num_inputs_ : 0),
      rows_(experiment.num_nodes(), 0) {
  size_t steps = 0;
  for (int k = 0; k < experiment.num_nodes(); ++k) {
    rows_[k] = 3 * steps;
    if (k < static_cast<int>(experiment.node_substeps.size())) {
      steps += static_cast<size_t>(experiment.node_substeps[k]);
    }
  }
}

void NodeInputs::Append(size_t k, std::vector<std::vector<double>>* inputs) const {
  if (cache_rows_ == 0) return;
  const size_t row = k < rows_.size() ? std::min(rows_[k], cache_rows_ - 1) : cache_rows_ - 1;
  for (size_t u = 0; u < num_inputs_; ++u) {
    (*inputs)[u].push_back(experiment_.input_cache[row * num_inputs_ + u]);
  }
}

std::vector<ResidualAnalysis> AnalyseFitResiduals(const ModelInfo& info,
                                                  const std::vector<Experiment>& experiments,
                                                  const std::vector<ExperimentFit>& fits) {
  std::map<std::string, const Experiment*> by_name;
  for (const Experiment& e : experiments) by_name[e.name] = &e;
  std::vector<ResidualAnalysis> analyses;
  std::vector<double> t, e;
  for (const ExperimentFit& fit : fits) {
    auto found = by_name.find(fit.experiment);
    if (fit.diverged || found == by_name.end()) continue;
    const Experiment& experiment = *found->second;
    const NodeInputs fed_inputs(experiment);
    for (size_t o = 0; o < info.outputs.size(); ++o) {
      const int measured = Column(fit.trace, info.outputs[o] + "_measured");
      const int simulated = Column(fit.trace, info.outputs[o] + "_simulated");
      if (measured < 0 || simulated < 0) continue;
      const bool wrapped = experiment.Wrapped(static_cast<int>(o));
      t.clear();
      e.clear();
      std::vector<std::vector<double>> inputs(fed_inputs.count());
      const std::vector<double>& y = fit.trace.columns[measured];
      const std::vector<double>& y_sim = fit.trace.columns[simulated];
      // A held-out run's burn-in is not scored, and not analysed.
      const double scored_from = fit.start.burn_in > 0.0 && !fit.trace.t.empty()
                                     ? fit.trace.t.front() + fit.start.burn_in + 1e-9
                                     : -std::numeric_limits<double>::infinity();
      for (size_t k = 0; k < y.size() && k < fit.trace.t.size(); ++k) {
        if (!std::isfinite(y[k]) || !std::isfinite(y_sim[k])) continue;
        if (fit.trace.t[k] <= scored_from) continue;
        const double residual = y_sim[k] - y[k];
        t.push_back(fit.trace.t[k]);
        e.push_back(wrapped ? WrapAngle(residual) : residual);
        fed_inputs.Append(k, &inputs);
      }
      if (e.empty()) continue;
      std::vector<std::string> names;
      std::vector<std::vector<double>> fed;
      FedInputs(info, e.size(), &inputs, &names, &fed);
      analyses.push_back(AnalyseResiduals(fit.experiment, info.outputs[o], t, e, names, fed));
      for (const ChannelMetrics& m : fit.channels) {
        if (m.output == info.outputs[o])
          analyses.back().noise_free = NoiseFree(m.rmse, m.noise, m.r2);
      }
    }
  }
  return analyses;
}

std::vector<ResidualAnalysis> AnalyseInnovations(const OutputErrorProblem& problem) {
  std::vector<ResidualAnalysis> analyses;
  if (!problem.filter_error()) return analyses;
  const ModelInfo& info = problem.model().info();
  for (size_t x = 0; x < problem.experiments().size(); ++x) {
    const Experiment& experiment = problem.experiments()[x];
    FilterRun run;
    if (!problem.RunFilter(static_cast<int>(x), 0, &run)) continue;
    const NodeInputs fed_inputs(experiment);
    for (size_t o = 0; o < info.outputs.size(); ++o) {
      std::vector<double> t, e;
      std::vector<std::vector<double>> inputs(fed_inputs.count());
      for (int k = 0; k < experiment.num_nodes(); ++k) {
        for (int i = experiment.node_first_sample[k]; i < experiment.node_first_sample[k + 1]; ++i) {
          if (experiment.samples[i].output != static_cast<int>(o)) continue;
          t.push_back(experiment.node_time[k]);
          e.push_back(run.innovation[i] / std::sqrt(run.variance[i]));
          fed_inputs.Append(k, &inputs);
        }
      }
      if (e.empty()) continue;
      std::vector<std::string> names;
      std::vector<std::vector<double>> fed;
      FedInputs(info, e.size(), &inputs, &names, &fed);
      analyses.push_back(AnalyseResiduals(experiment.name, info.outputs[o], t, e, names, fed));
      analyses.back().innovations = true;
    }
  }
  return analyses;
}

}  // namespace vesselid

#include "engine/study/monte_carlo_noise.h"

#include <cmath>
#include <random>
#include <set>

#include "engine/run/records.h"
#include "engine/run/stage_weights.h"

namespace vesselid {

bool MonteCarloNoise::any_input() const {
  for (double sigma : input) {
    if (sigma > 0.0) return true;
  }
  return false;
}

bool ResolveMonteCarloNoise(const StudyStage& stage, const MonteCarloOptions& options,
                            const std::vector<std::vector<double>>* fit, MonteCarloNoise* noise,
                            std::string* error) {
  const ModelInfo& info = stage.model->info();
  noise->output.assign(info.outputs.size(), NAN);
  noise->input.assign(info.inputs.size(), 0.0);
  noise->output_of_fit.assign(info.outputs.size(), false);
  for (const auto& [name, value] : options.noise) {
    const int c = info.OutputIndex(name), u = info.InputIndex(name);
    if (c >= 0) {
      noise->output[c] = value;
    } else if (u >= 0) {
      noise->input[u] = value;
    } else {
      *error = "noise names '" + name + "', neither an output nor an input of model " + info.name;
      return false;
    }
  }
  if (fit != nullptr) {
    // Residual sums per output at the estimate; p free unknowns of the stage's problem.
    std::vector<double> squares(info.outputs.size(), 0.0);
    std::vector<int> counts(info.outputs.size(), 0);
    int samples = 0;
    for (size_t e = 0; e < stage.experiments.size(); ++e) {
      const Experiment& experiment = stage.experiments[e];
      for (size_t i = 0; i < experiment.samples.size(); ++i) {
        const ExperimentSample& s = experiment.samples[i];
        double r = (*fit)[e][i] - s.value;
        if (experiment.Wrapped(s.output)) r = std::remainder(r, 2.0 * M_PI);
        squares[s.output] += r * r;
        ++counts[s.output];
        ++samples;
      }
    }
    auto problem = OutputErrorProblem::Create(stage.model, stage.experiments, stage.specs,
                                              stage.stage->problem, error);
    if (problem == nullptr) return false;
    const double unknowns = problem->num_free();
    for (size_t c = 0; c < info.outputs.size(); ++c) {
      if (counts[c] == 0 || std::isfinite(noise->output[c])) continue;
      const double dof = counts[c] - unknowns * counts[c] / samples;
      if (!(dof > 0.0)) {
        *error = "output '" + info.outputs[c] + "' has " + std::to_string(counts[c]) +
                 " samples, too few beside the stage's " + std::to_string(problem->num_free()) +
                 " unknowns to estimate its noise level; give it in noise";
        return false;
      }
      noise->output[c] = std::sqrt(squares[c] / dof);
      noise->output_of_fit[c] = true;
    }
  }
  for (const Experiment& e : stage.experiments) {
    for (size_t c = 0; c < info.outputs.size(); ++c) {
      if (e.output_sample_count[c] > 0 && !std::isfinite(noise->output[c])) {
        *error = "no noise for output '" + info.outputs[c] + "' (compared in experiment '" +
                 e.name + "')";
        return false;
      }
    }
  }
  return true;
}

bool NoisyInputExperiments(const StudyStage& stage, const std::vector<double>& input_sigma,
                           unsigned seed, std::vector<Experiment>* experiments,
                           std::string* error) {
  const RunConfig& config = *stage.config;
  const ModelInfo& info = stage.model->info();
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const std::string& name : stage.stage->experiments) {
    if (stage.records.Find(name) == nullptr) {
      *error = "experiment '" + name + "' was not read";
      return false;
    }
  }
  // A record shared by experiments (windows of one log) gets one noise draw.
  const auto add_noise = [&](const std::string& name, Trajectory* record) {
    const ExperimentSpec* spec = config.FindExperiment(name);
    Trajectory& data = *record;
    std::set<int> noisy;  // a column read by two inputs gets its noise once
    for (size_t u = 0; u < info.inputs.size(); ++u) {
      const auto column = spec->inputs.find(info.inputs[u]);
      if (!(input_sigma[u] > 0.0) || column == spec->inputs.end()) continue;
      const int c = data.Find(column->second);
      if (c < 0 || !noisy.insert(c).second) continue;
      for (double& value : data.columns[c]) {
        if (!std::isnan(value)) value += input_sigma[u] * normal(random);
      }
    }
  };
  TrajectoryCache records = stage.records.EditedCopy(stage.stage->experiments, add_noise);
  if (!PrepareExperiments(config, stage.stage->experiments, *stage.model,
                          StageExperimentOptions(config, *stage.stage), &records, experiments,
                          error)) {
    return false;
  }
  bool same = experiments->size() == stage.experiments.size();
  for (size_t e = 0; same && e < experiments->size(); ++e) {
    same = (*experiments)[e].name == stage.experiments[e].name &&
           (*experiments)[e].samples.size() == stage.experiments[e].samples.size();
  }
  if (!same) {
    *error =
        "with the noisy input the records are cut into other experiments than the "
        "stage's (input_range)";
    return false;
  }
  return true;
}

}  // namespace vesselid

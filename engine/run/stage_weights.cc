#include "engine/run/stage_weights.h"

#include <algorithm>
#include <set>
#include <string>

#include "engine/solve/noise_weights.h"

namespace vesselid {

int ComparedOutputCount(const RunConfig& config, const StageConfig& stage) {
  if (!stage.experiment.outputs.empty()) {
    return static_cast<int>(
        std::set<std::string>(stage.experiment.outputs.begin(), stage.experiment.outputs.end())
            .size());
  }
  std::set<std::string> outputs;
  for (const std::string& name : stage.experiments) {
    const ExperimentSpec* spec = config.FindExperiment(name);
    if (spec == nullptr) continue;
    for (const auto& [output, column] : spec->outputs) outputs.insert(output);
  }
  return static_cast<int>(outputs.size());
}

bool UsesNoiseWeights(const RunConfig& config, const StageConfig& stage) {
  if (stage.kind != StageConfig::Kind::kOutputError) return false;
  // The filter-error method estimates each output's noise in its likelihood.
  if (stage.problem.disturbance.method == DisturbanceSpec::Method::kFilterError) return false;
  switch (stage.weights) {
    case StageConfig::Weights::kNoise:
      return true;
    case StageConfig::Weights::kGiven:
      return false;
    case StageConfig::Weights::kDefault:
      break;
  }
  return ComparedOutputCount(config, stage) >= 2;
}

ExperimentOptions StageExperimentOptions(const RunConfig& config, const StageConfig& stage) {
  ExperimentOptions options = stage.experiment;
  if (UsesNoiseWeights(config, stage) && !stage.normalize_by_length_set) {
    options.normalize_by_length = false;
  }
  return options;
}

void SetFirstSolveWeights(const RunConfig& config, const StageConfig& stage,
                          OutputErrorProblem* problem) {
  if (!UsesNoiseWeights(config, stage)) return;
  for (const ExperimentSpec& spec : config.experiments) {
    const bool in_stage = std::find(stage.experiments.begin(), stage.experiments.end(),
                                    spec.name) != stage.experiments.end();
    if (in_stage && !spec.output_weights.empty()) return;
  }
  SetDataNoiseWeights(problem);
}

}  // namespace vesselid

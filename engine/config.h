// A run as a YAML config describes it, parsed at the edge into plain structs.
//
//   model:       {family: nomoto, type: second_order, ...family keys}
//   simulation:  family-specific description of synthetic experiments (`vesselid simulate`)
//   experiments: [{name, file, inputs, outputs, interpolation, weights, initial_state,
//                  degrees, window}]
//   stages:      [{name, experiments, outputs, parameters, free_initial_states, loss,
//                  integration, normalize_by_length, global, local, uncertainty}]
//
// Every key is checked; an unknown key, a name the model does not have, inverted bounds or a
// start outside them is an error naming file, line and key.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/experiment.h"
#include "engine/model_registry.h"
#include "engine/output_error_problem.h"
#include "engine/parameter.h"
#include "engine/stage.h"

namespace vesselid {

struct StageConfig {
  StageOptions options;
  std::vector<std::string> experiments;  // names from RunConfig::experiments
  std::vector<ParameterSpec> parameters;
  OutputErrorOptions problem;
  ExperimentOptions experiment;  // compared outputs, step bound, length normalisation
};

struct RunConfig {
  std::string path;
  std::string description;
  std::string family;
  std::shared_ptr<const ModelHandle> model;
  const ModelFamily* model_family = nullptr;
  YAML::Node simulation;  // handed to the family's simulator, parsed there
  std::vector<ExperimentSpec> experiments;
  std::vector<StageConfig> stages;

  const ExperimentSpec* FindExperiment(const std::string& name) const;
};

// Experiment files are resolved against data_dir when it is not empty, else against the
// config file's folder.
bool LoadRunConfig(const std::string& path, const std::string& data_dir,
                   const ModelRegistry& registry, RunConfig* config, std::string* error);

}  // namespace vesselid

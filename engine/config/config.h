// A config file, parsed at the edge into plain structs: the staged run (run/run_config.h),
// the studies (study/study_options.h), the model family and its simulation map.
//
//   model:       {family: nomoto, type: second_order, ...family keys}
//   simulation:  family-specific description of synthetic experiments (`vesselid simulate`)
//   experiment_defaults: keys merged into every experiment (experiment_templates.h)
//   experiments: [{name, file | files, inputs, outputs, interpolation, weights, initial_state,
//                  degrees, window, time, position, screen, resample}]
//                  (the last four: experiment_data_config.h)
//   sets:        {<name>: [experiments]}, usable as any list of experiments (experiment_sets.h)
//   stages:      [{name, type, least_squares, model, experiments, validation, outputs,
//                  parameters,
//                  free_initial_states, loss, integration, normalize_by_length, continuation,
//                  global, local, uncertainty}]
//   fusion:      inverse_variance | mean | information (fusion.h)
//   final_validation: {experiments, outputs, model, free_initial_states}
//   study:       {seed, threads, profile, monte_carlo, starts, partitions}  (`vesselid study`,
//                 study_options.h)
//
// A stage's `model` map overrides keys of the run's `model` map (e.g. active DOFs). A
// parameter without `start` starts from its latest estimate in an earlier stage (else the
// model default); parameters a stage does not list are held at that value.
//
// YAML merge keys (`<<: *anchor`) are resolved first (yaml_merge.h). Every key is checked;
// an unknown key, a name the model does not have, inverted bounds or a start outside them is
// an error naming file, line and key.
#pragma once

#include <memory>
#include <set>
#include <string>

#include "engine/config/model_registry.h"
#include "engine/run/run_config.h"
#include "engine/study/study_options.h"

namespace vesselid {

struct SimulationSection;

struct ConfigFile {
  RunConfig run;
  StudyConfig study;                   // empty when the config has no study section
  const ModelFamily* family = nullptr;  // the registry's entry for run.family
  // The family's `simulation` map (simulation_section.h); null when the config has none.
  std::shared_ptr<const SimulationSection> simulation;
};

// Where a config comes from.
struct ConfigSource {
  std::string path;  // the config file; with `text`, the name messages give it
  std::string text;  // the config itself (YAML or JSON); empty: read from `path`
  // Experiment files are resolved against it when it is not empty, else against the folder
  // of `path` (the working folder for a config given as text without a path).
  std::string data_dir;
  // Experiments whose records the caller hands over in memory (ExperimentSpec::table, as
  // the Python package does): their `file` key may be absent.
  std::set<std::string> in_memory;
  // Read `final_validation.reference` (another run's results.json). False for a command that
  // does not validate (simulate): the reference run need not exist yet, and only its folder
  // is kept.
  bool read_reference = true;
};

bool LoadConfig(const ConfigSource& source, const ModelRegistry& registry, ConfigFile* config,
                std::string* error);

// Experiment files are resolved against data_dir when it is not empty, else against the
// config file's folder. The registry must outlive `config` (config->family points into it).
bool LoadConfigFile(const std::string& path, const std::string& data_dir,
                    const ModelRegistry& registry, ConfigFile* config, std::string* error,
                    bool read_reference = true);

// The run part of a config file alone.
bool LoadRunConfig(const std::string& path, const std::string& data_dir,
                   const ModelRegistry& registry, RunConfig* config, std::string* error);

// Writes the config's synthetic experiments (its `simulation` map) into out_dir through its
// family (with check_only: reads and checks the map, writes nothing); a config error names
// the file, line and key.
bool SimulateConfig(const ConfigFile& config, const std::string& out_dir, std::string* error,
                    bool check_only = false);

}  // namespace vesselid

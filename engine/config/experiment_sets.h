// Named sets of experiments, written once and used wherever a list of experiments is: a
// stage's `experiments` and `validation`, `final_validation.experiments`, a partition study's
// `experiments`, and the sets below them.
//
//   sets: {held_out: [zz3, zz7], training: [zz1, zz2, zz4]}
//   validation: held_out          # a set's name alone
//   validation: [held_out, zz9]   # experiments and sets mixed; each experiment once
#pragma once

#include <string>
#include <vector>

#include "engine/config/yaml_reader.h"
#include "engine/run/run_config.h"

namespace vesselid {

// The `sets` map into config->experiment_sets, after the experiments: each set a list as
// ExperimentNames reads it (so a set may use the sets above it), not empty, not named like an
// experiment.
void ReadExperimentSets(const YamlReader& reader, const YAML::Node& node, RunConfig* config);

// A list of experiment names at `key`: the name of a set, or a list of experiment and set
// names, each expanded in order. An unknown name, or an experiment listed twice, is an error
// naming the file, line and key.
std::vector<std::string> ExperimentNames(const YamlReader& reader, const YAML::Node& node,
                                         const std::string& key, const RunConfig& config);

}  // namespace vesselid

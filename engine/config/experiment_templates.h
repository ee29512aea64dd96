// Experiment templates of a config: defaults merged into every experiment, and a file
// pattern making one experiment per matching file.
//
//   experiment_defaults: {file: campaign.csv, inputs: {delta: delta}, outputs: {psi: psi}}
//   experiments:
//     - {name: a, window: [0, 60]}               # the defaults with a window
//     - {files: "zz_*.csv", name: "zz_{stem}"}   # zz_zz_1, zz_zz_2, ... (sorted file names)
//
// Defaults: maps (inputs, outputs, weights, segments, ...) merge key by key, recursively;
// lists (degrees, window, wrap) and scalars replace; an experiment's key set to null
// (`window: ~`) drops the default; an experiment's own `file` or `files` replaces a default
// `file`. `files` is a POSIX glob (*, ?, [...]) relative to the data folder (--data, else the
// config's folder); `name` defaults to "{stem}", the file name without its extension.
#pragma once

#include <string>
#include <vector>

#include "engine/config/yaml_reader.h"

namespace vesselid {

// The keys an experiment map may hold.
const std::vector<std::string>& ExperimentKeys();

struct ExperimentEntry {
  YAML::Node node;   // the experiment's map, defaults merged, `files` replaced by one `file`
  std::string path;  // for messages: "experiments[2]", or "experiments[2](zz_3)" for a file
                     // of a pattern
};

// The config's `experiments` with `experiment_defaults` merged and `files` expanded. Nodes it
// builds are placed (YamlReader::Place) where they were written. Fails on a missing list,
// defaults that are not an experiment's keys, a pattern no file matches, `file` beside
// `files`, or a name without {stem} for a pattern.
std::vector<ExperimentEntry> ExpandExperiments(YamlReader* reader, const YAML::Node& root,
                                               const std::string& data_folder);

}  // namespace vesselid

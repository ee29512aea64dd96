// Readers of config sections shared by the files that parse a run config (config.cc,
// study_config.cc). Each fails through YamlReader with the file, line and key.
#pragma once

#include <string>
#include <vector>

#include "engine/config.h"
#include "engine/yaml_reader.h"

namespace vesselid {

// `global: {algorithm, max_evaluations, max_time, seed, population, candidates,
// min_separation}` over the values already in `global`.
void ReadGlobal(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                GlobalStartOptions* global);

// A list of experiment names, each configured.
std::vector<std::string> ExperimentNames(const YamlReader& reader, const YAML::Node& node,
                                         const std::string& key, const RunConfig& config);

// The `study` section (study_options.h).
StudyConfig ReadStudy(const YamlReader& reader, const YAML::Node& node, const RunConfig& config);

}  // namespace vesselid

// A model family as the config reader sees it: how it builds its model from the config's
// `model` map and simulates the experiments of its `simulation` map. Families register one
// (problems/*/..._config.h) in a ModelRegistry (model_registry.h).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "engine/config/yaml_reader.h"
#include "engine/model/model_handle.h"

namespace vesselid {

struct ModelFamily {
  std::string name;
  std::string description;
  // Builds the model from the `model` map at `path`; config errors are thrown as ConfigError.
  std::function<std::unique_ptr<ModelHandle>(const YamlReader& reader, const YAML::Node& model,
                                             const std::string& path)>
      make_model;
  // Writes the experiments described by the `simulation` map as CSV files into out_dir, or
  // with `check_only` reads and checks the map (its work against reader.limits() included)
  // and writes nothing. Config errors are thrown as ConfigError; I/O errors are returned.
  std::function<bool(const YamlReader& reader, const YAML::Node& simulation,
                     const ModelHandle& model, const std::string& out_dir, bool check_only,
                     std::string* error)>
      simulate;
};

}  // namespace vesselid

// The model families a run can name in its `model.family` key. Each family builds its model
// from the config's `model` map and can simulate the experiments of its `simulation` map.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

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

class ModelRegistry {
 public:
  void Register(ModelFamily family) { families_.push_back(std::move(family)); }
  const ModelFamily* Find(const std::string& name) const;
  std::vector<std::string> Names() const;

  // The model of family `family` with the options of its config map as plain text, e.g.
  // MakeModel("nomoto", {{"type", "second_order"}}) or {{"dofs", "[surge, sway, yaw]"}}
  // (each value is read as the config would read it). Null with the config's message
  // ("model.type: unknown type ...") in `error` when the family or an option is wrong.
  std::shared_ptr<const ModelHandle> MakeModel(const std::string& family,
                                               const std::map<std::string, std::string>& options,
                                               std::string* error) const;

 private:
  std::vector<ModelFamily> families_;
};

}  // namespace vesselid

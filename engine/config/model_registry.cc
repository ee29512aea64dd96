#include "engine/config/model_registry.h"

#include "engine/config/model_family.h"

namespace vesselid {

void ModelRegistry::Register(ModelFamily family) {
  families_.push_back(std::make_shared<const ModelFamily>(std::move(family)));
}

const ModelFamily* ModelRegistry::Find(const std::string& name) const {
  for (const auto& family : families_) {
    if (family->name == name) return family.get();
  }
  return nullptr;
}

std::vector<std::string> ModelRegistry::Names() const {
  std::vector<std::string> names;
  for (const auto& family : families_) names.push_back(family->name);
  return names;
}

std::shared_ptr<const ModelHandle> ModelRegistry::MakeModel(
    const std::string& family, const std::map<std::string, std::string>& options,
    std::string* error) const {
  const ModelFamily* entry = Find(family);
  if (entry == nullptr) {
    std::string names;
    for (const std::string& name : Names()) names += (names.empty() ? "" : ", ") + name;
    *error = "unknown model family '" + family + "' (" + names + ")";
    return nullptr;
  }
  // The options become the `model` map a config would hold, read by the family's reader.
  YAML::Node model(YAML::NodeType::Map);
  model["family"] = family;
  try {
    for (const auto& [key, value] : options) model[key] = YAML::Load(value);
    const YamlReader reader("model options");
    return std::shared_ptr<const ModelHandle>(entry->make_model(reader, model, "model"));
  } catch (const ConfigError& e) {
    *error = e.what();
  } catch (const YAML::Exception& e) {
    *error = "model options: " + e.msg;
  }
  return nullptr;
}

}  // namespace vesselid

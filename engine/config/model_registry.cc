#include "engine/config/model_registry.h"

namespace vesselid {

const ModelFamily* ModelRegistry::Find(const std::string& name) const {
  for (const ModelFamily& family : families_) {
    if (family.name == name) return &family;
  }
  return nullptr;
}

std::vector<std::string> ModelRegistry::Names() const {
  std::vector<std::string> names;
  for (const ModelFamily& family : families_) names.push_back(family.name);
  return names;
}

}  // namespace vesselid

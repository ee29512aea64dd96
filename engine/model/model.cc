#include "engine/model/model.h"

namespace vesselid {
namespace {

int IndexOf(const std::vector<std::string>& names, const std::string& name) {
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

int ModelInfo::ParameterIndex(const std::string& name) const { return IndexOf(parameters, name); }
int ModelInfo::StateIndex(const std::string& name) const { return IndexOf(states, name); }
int ModelInfo::InputIndex(const std::string& name) const { return IndexOf(inputs, name); }
int ModelInfo::OutputIndex(const std::string& name) const { return IndexOf(outputs, name); }

std::string JoinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) {
    if (!joined.empty()) joined += ", ";
    joined += name;
  }
  return joined;
}

}  // namespace vesselid

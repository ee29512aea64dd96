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

namespace {
std::string UnitAt(const std::vector<std::string>& units, int index) {
  return index >= 0 && index < static_cast<int>(units.size()) ? units[index] : std::string();
}
}  // namespace

std::string ModelInfo::OutputUnit(int index) const {
  const std::string unit = UnitAt(output_units, index);
  if (!unit.empty()) return unit;
  const bool angle =
      index >= 0 && index < static_cast<int>(angle_outputs.size()) && angle_outputs[index];
  return angle ? "rad" : "";
}

std::string ModelInfo::StateUnit(int index) const {
  const std::string unit = UnitAt(state_units, index);
  if (!unit.empty() || index < 0 || index >= static_cast<int>(states.size())) return unit;
  return OutputUnit(OutputIndex(states[index]));
}

std::string ModelInfo::InputUnit(int index) const { return UnitAt(input_units, index); }

std::string ModelInfo::ParameterUnit(int index) const { return UnitAt(parameter_units, index); }

std::pair<int, int> ModelInfo::TrackOutputs() const {
  std::vector<int> metres;
  for (int i = 0; i < static_cast<int>(outputs.size()) && metres.size() < 2; ++i) {
    if (OutputUnit(i) == "m") metres.push_back(i);
  }
  return metres.size() == 2 ? std::pair{metres[0], metres[1]} : std::pair{-1, -1};
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names) {
    if (!joined.empty()) joined += ", ";
    joined += name;
  }
  return joined;
}

}  // namespace vesselid

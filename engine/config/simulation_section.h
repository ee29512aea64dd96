// A config's `simulation` map as read, its marks kept for messages: what ConfigFile holds for
// SimulateConfig and the study reader. Only the config reader and the families see YAML.
#pragma once

#include "yaml-cpp/yaml.h"

namespace vesselid {

struct SimulationSection {
  YAML::Node node;
};

}  // namespace vesselid

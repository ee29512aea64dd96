#include "engine/run/display_units.h"

#include <algorithm>
#include <cmath>

namespace vesselid {

DisplayUnit OutputDisplayUnit(const RunConfig& config, const std::string& experiment,
                              const std::string& output) {
  const ModelInfo& info = config.model->info();
  DisplayUnit shown{info.OutputUnit(info.OutputIndex(output)), 1.0};
  const ExperimentSpec* spec =
      config.FindExperiment(RecordName(experiment));
  if (spec == nullptr || shown.unit.compare(0, 3, "rad") != 0) return shown;
  const auto column = spec->outputs.find(output);
  if (column == spec->outputs.end()) return shown;
  const std::vector<std::string>& degrees = spec->degree_columns;
  if (std::find(degrees.begin(), degrees.end(), column->second) == degrees.end()) return shown;
  return {"deg" + shown.unit.substr(3), 180.0 / M_PI};
}

std::string WithUnit(const std::string& label, const std::string& unit) {
  return unit.empty() ? label : label + " [" + unit + "]";
}

}  // namespace vesselid

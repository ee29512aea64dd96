#include "engine/run/display_units.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

namespace vesselid {

namespace {

// Whether `spec` reads model channel `channel` (an input or an output) from a column listed in
// its `degrees:`; nullopt when it does not map the channel.
std::optional<bool> ReadInDegrees(const ExperimentSpec& spec, const std::string& channel) {
  const std::map<std::string, std::string>& map =
      spec.outputs.count(channel) ? spec.outputs : spec.inputs;
  const auto column = map.find(channel);
  if (column == map.end()) return std::nullopt;
  const std::vector<std::string>& degrees = spec.degree_columns;
  return std::find(degrees.begin(), degrees.end(), column->second) != degrees.end();
}

DisplayUnit InDegrees(const std::string& unit) { return {"deg" + unit.substr(3), 180.0 / M_PI}; }

bool IsRadians(const std::string& unit) { return unit.compare(0, 3, "rad") == 0; }

// "unit^2/s", parenthesised where the unit is compound.
std::string SquaredPerSecond(const std::string& unit) {
  if (unit.empty()) return "";
  return (unit.find_first_of("/^*") == std::string::npos ? unit : "(" + unit + ")") + "^2/s";
}

// The unit of a disturbance parameter "<kind>.<part>.<output or state>" (disturbance.h): an
// SD in its output's unit (and an angle of it), a time constant in s, a peak frequency in
// rad/s, a damping ratio without one, a spectral density in unit^2/s. False for other names.
bool NoiseUnit(const ModelInfo& info, const std::string& name, std::string* unit,
               std::string* channel) {
  const size_t last = name.rfind('.');
  if (last == std::string::npos) return false;
  const std::string head = name.substr(0, last), target = name.substr(last + 1);
  const std::string output_unit = info.OutputUnit(info.OutputIndex(target));
  if (head == "sigma.white" || head == "sigma.ar1" || head == "sigma.wave") {
    *unit = output_unit;
    *channel = target;
  } else if (head == "tau.ar1") {
    *unit = "s";
  } else if (head == "omega.wave") {
    *unit = "rad/s";
  } else if (head == "zeta.wave") {
    *unit = "";
  } else if (head == "q.bias") {
    *unit = SquaredPerSecond(output_unit);
  } else if (head == "q.process") {
    *unit = SquaredPerSecond(info.StateUnit(info.StateIndex(target)));
  } else {
    return false;
  }
  return true;
}

}  // namespace

DisplayUnit OutputDisplayUnit(const RunConfig& config, const std::string& experiment,
                              const std::string& output) {
  const ModelInfo& info = config.model->info();
  DisplayUnit shown{info.OutputUnit(info.OutputIndex(output)), 1.0};
  const ExperimentSpec* spec =
      config.FindExperiment(RecordName(experiment));
  if (spec == nullptr || !IsRadians(shown.unit) || !spec->outputs.count(output)) return shown;
  return ReadInDegrees(*spec, output).value_or(false) ? InDegrees(shown.unit) : shown;
}

std::string ParameterModelUnit(const ModelInfo& info, const std::string& name,
                               std::string* channel) {
  std::string base = name.substr(0, name.find('['));
  std::string follows;
  std::string unit;
  if (base.compare(0, 3, "x0.") == 0) {
    base = base.substr(3);
    unit = info.StateUnit(info.StateIndex(base));
    if (info.OutputIndex(base) >= 0) follows = base;
  } else if (info.ParameterIndex(base) < 0 && NoiseUnit(info, base, &unit, &follows)) {
    // a filter-error stage's disturbance parameter (DisturbanceLayout::Names)
  } else {
    unit = info.ParameterUnit(info.ParameterIndex(base));
    const auto at = info.parameter_channels.find(base);
    if (at != info.parameter_channels.end()) follows = at->second;
  }
  if (channel != nullptr) *channel = follows;
  return unit;
}

DisplayUnit ParameterDisplayUnit(const RunConfig& config, const std::string& name) {
  const size_t open = name.find('[');
  const std::string experiment =
      open == std::string::npos ? "" : name.substr(open + 1, name.size() - open - 2);
  std::string channel;
  const DisplayUnit shown{ParameterModelUnit(config.model->info(), name, &channel), 1.0};
  if (channel.empty() || !IsRadians(shown.unit)) return shown;
  if (!experiment.empty()) {
    const ExperimentSpec* spec = config.FindExperiment(RecordName(experiment));
    return spec && ReadInDegrees(*spec, channel).value_or(false) ? InDegrees(shown.unit) : shown;
  }
  bool mapped = false;
  for (const ExperimentSpec& spec : config.experiments) {
    const std::optional<bool> degrees = ReadInDegrees(spec, channel);
    if (degrees && !*degrees) return shown;
    mapped = mapped || degrees.has_value();
  }
  return mapped ? InDegrees(shown.unit) : shown;
}

std::vector<std::string> DegreeChannels(const RunConfig& config) {
  std::vector<std::string> names;
  if (config.experiments.empty()) return names;
  const ModelInfo& info = config.model->info();
  for (const std::vector<std::string>* channels : {&info.inputs, &info.outputs}) {
    for (const std::string& channel : *channels) {
      if (ReadInDegrees(config.experiments.front(), channel).value_or(false)) {
        names.push_back(channel);
      }
    }
  }
  return names;
}

DisplayUnitOf OutputUnits(const RunConfig& config) {
  return [&config](const std::string& experiment, const std::string& output) {
    return OutputDisplayUnit(config, experiment, output);
  };
}

ParameterUnitOf ParameterUnits(const RunConfig& config) {
  return [&config](const std::string& name) { return ParameterDisplayUnit(config, name); };
}

std::string ShownValue(double value, const DisplayUnit& unit, const char* format) {
  char text[64];
  std::snprintf(text, sizeof(text), format, unit.scale * value);
  return unit.unit.empty() ? std::string(text) : std::string(text) + " " + unit.unit;
}

std::string WithUnit(const std::string& label, const std::string& unit) {
  return unit.empty() ? label : label + " [" + unit + "]";
}

}  // namespace vesselid

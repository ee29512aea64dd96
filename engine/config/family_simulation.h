// What every family's `simulation` reader does alike (problems/*/..._config.cc): the `truth`
// map over the model's parameters, angles given in degrees, and the folder the CSV files go to.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "engine/config/yaml_reader.h"
#include "engine/model/model.h"

namespace vesselid {

// `defaults` with the values of the `truth` map at `path` (absent: unchanged); every key must
// be a parameter of the model (an error naming file, line and key otherwise).
inline std::vector<double> ReadTruth(const YamlReader& reader, const YAML::Node& truth,
                                     const std::string& path, const ModelInfo& info,
                                     std::vector<double> defaults) {
  if (!truth) return defaults;
  reader.CheckMap(truth, path, info.parameters);
  for (const auto& item : truth) {
    const std::string name = item.first.as<std::string>();
    defaults[info.ParameterIndex(name)] = reader.Double(item.second, Child(path, name));
  }
  return defaults;
}

// An angle given in degrees at map[name] into *radians (kept when absent).
inline void ReadDegrees(const YamlReader& reader, const YAML::Node& map, const std::string& path,
                        const std::string& name, double* radians) {
  constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;
  double degrees = *radians / kRadiansPerDegree;
  reader.Read(map, path, name, &degrees);
  *radians = degrees * kRadiansPerDegree;
}

// Creates out_dir (and its parents); false with "<dir>: cannot create folder: <why>".
inline bool CreateSimulationFolder(const std::string& out_dir, std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) *error = out_dir + ": cannot create folder: " + ec.message();
  return !ec;
}

}  // namespace vesselid

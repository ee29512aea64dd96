#include "engine/config/experiment_data_config.h"

#include <map>

#include "engine/config/config_sections.h"

namespace vesselid {
namespace {

void ReadTime(const YamlReader& reader, const YAML::Node& n, const std::string& key,
              ExperimentSpec* spec) {
  reader.CheckMap(n, key, {"column", "unit"});
  reader.Read(n, key, "column", &spec->csv.time_column);
  if (spec->csv.time_column.empty()) reader.Fail(n["column"], Child(key, "column"), "is empty");
  if (const YAML::Node unit = n["unit"]) {
    const std::string text = reader.String(unit, Child(key, "unit"));
    const std::map<std::string, double> scales = {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6},
                                                  {"min", 60.0}};
    const auto found = scales.find(text);
    if (found == scales.end())
      reader.Fail(unit, Child(key, "unit"), "unknown unit '" + text + "' (s, ms, us, min)");
    spec->data.time_scale = found->second;
  }
}

void ReadPosition(const YamlReader& reader, const YAML::Node& n, const std::string& key,
                  ExperimentSpec* spec) {
  reader.CheckMap(n, key, {"lat", "lon", "origin"});
  GnssPositionOptions& g = spec->data.gnss;
  for (const char* column : {"lat", "lon"}) {
    if (!n[column]) reader.Fail(n, key, std::string("missing key '") + column + "'");
  }
  g.lat_column = reader.String(n["lat"], Child(key, "lat"));
  g.lon_column = reader.String(n["lon"], Child(key, "lon"));
  g.key = key;
  if (const YAML::Node origin = n["origin"]) {
    const std::string where = Child(key, "origin");
    if (origin.IsScalar()) {
      if (reader.String(origin, where) != "first") {
        reader.Fail(origin, where, "expected first or [lat, lon] in degrees");
      }
    } else {
      const std::vector<double> at = reader.Doubles(origin, where);
      if (at.size() != 2) reader.Fail(origin, where, "expected first or [lat, lon] in degrees");
      if (!(at[0] >= -90.0 && at[0] <= 90.0)) {
        reader.Fail(origin[0], Child(where, 0), "latitude must be in [-90, 90]");
      }
      if (!(at[1] >= -180.0 && at[1] <= 360.0)) {
        reader.Fail(origin[1], Child(where, 1), "longitude must be in [-180, 360]");
      }
      g.origin_first = false;
      g.origin_lat = at[0];
      g.origin_lon = at[1];
    }
  }
  spec->data.position = true;
}

void ReadScreen(const YamlReader& reader, const YAML::Node& n, const std::string& key,
                const ModelInfo& info, ExperimentSpec* spec) {
  reader.CheckMap(n, key, {"max_speed", "max_rate", "stale", "zero_fix"});
  ExperimentDataSpec& d = spec->data;
  d.screen = true;
  d.screen_key = key;
  reader.Read(n, key, "max_speed", &d.max_speed);
  if (!(d.max_speed >= 0.0)) reader.Fail(n["max_speed"], Child(key, "max_speed"), "must be >= 0");
  if (const YAML::Node rates = n["max_rate"]) {
    const std::string where = Child(key, "max_rate");
    d.max_rate = reader.DoubleMap(rates, where);
    std::vector<std::string> outputs;
    for (const auto& [output, rate] : d.max_rate) {
      outputs.push_back(output);
      if (!(rate > 0.0)) reader.Fail(rates[output], Child(where, output), "must be > 0");
      if (spec->outputs.count(output) == 0) {
        reader.Fail(rates[output], Child(where, output),
                    "output '" + output + "' is not mapped to a column");
      }
    }
    CheckNames(reader, rates, where, outputs, info.outputs, "output", info);
  }
  reader.Read(n, key, "stale", &d.stale);
  if (n["stale"] && d.stale < 2) reader.Fail(n["stale"], Child(key, "stale"), "must be >= 2");
  reader.Read(n, key, "zero_fix", &d.zero_fix);
  d.zero_fix_given = static_cast<bool>(n["zero_fix"]);
}

void ReadResample(const YamlReader& reader, const YAML::Node& n, const std::string& key,
                  ExperimentSpec* spec) {
  reader.CheckMap(n, key, {"rate", "max_gap"});
  if (!n["rate"]) reader.Fail(n, key, "missing key 'rate'");
  reader.Read(n, key, "rate", &spec->data.resample_rate);
  if (!(spec->data.resample_rate > 0.0)) {
    reader.Fail(n["rate"], Child(key, "rate"), "must be > 0 (Hz)");
  }
  reader.Read(n, key, "max_gap", &spec->data.resample_max_gap);
  if (!(spec->data.resample_max_gap >= 1.0)) {
    reader.Fail(n["max_gap"], Child(key, "max_gap"), "must be >= 1 (sample intervals)");
  }
}

}  // namespace

void ReadExperimentData(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                        const ModelInfo& info, ExperimentSpec* spec) {
  if (const YAML::Node n = node["time"]) ReadTime(reader, n, Child(path, "time"), spec);
  if (const YAML::Node n = node["position"]) ReadPosition(reader, n, Child(path, "position"), spec);
  if (const YAML::Node n = node["screen"]) ReadScreen(reader, n, Child(path, "screen"), info, spec);
  if (const YAML::Node n = node["resample"]) ReadResample(reader, n, Child(path, "resample"), spec);
  for (size_t o = 0; o < info.outputs.size() && o < info.angle_outputs.size(); ++o) {
    if (info.angle_outputs[o]) spec->data.angle_outputs.push_back(info.outputs[o]);
  }
}

}  // namespace vesselid

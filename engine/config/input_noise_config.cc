#include "engine/config/input_noise_config.h"

namespace vesselid {
namespace {

// `auto` (0), or a positive number; `off` (-1) where allowed.
double PositiveOrAuto(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                      bool off_allowed) {
  if (node.IsScalar() && node.Scalar() == "auto") return 0.0;
  if (off_allowed && node.IsScalar() && node.Scalar() == "off") return -1.0;
  if (!node.IsScalar()) {
    reader.Fail(node, key, off_allowed ? "expected auto, off or a positive number"
                                       : "expected auto or a positive number");
  }
  const double value = reader.Double(node, key);
  if (!(value > 0.0)) reader.Fail(node, key, "must be > 0 (or auto)");
  return value;
}

}  // namespace

void ReadInputNoise(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                    const ModelInfo& info, ExperimentSpec* spec) {
  reader.CheckMap(node, path, info.inputs);
  for (const auto& item : node) {
    const std::string input = reader.KeyName(item.first, path);
    const std::string key = Child(path, input);
    if (spec->inputs.count(input) == 0) {
      reader.Fail(item.second, key, "input '" + input + "' is not mapped to a column");
    }
    InputNoiseSpec noise;
    noise.key = reader.Where(item.second, key);
    const YAML::Node& value = item.second;
    if (value.IsScalar()) {
      if (value.Scalar() != "auto") {
        reader.Fail(value, key, "expected auto or a map {sigma, knots, correction}");
      }
    } else {
      reader.CheckMap(value, key, {"sigma", "knots", "correction"});
      if (value["sigma"]) {
        noise.sigma = PositiveOrAuto(reader, value["sigma"], Child(key, "sigma"), false);
      }
      if (value["knots"]) {
        noise.knots = PositiveOrAuto(reader, value["knots"], Child(key, "knots"), false);
      }
      if (value["correction"]) {
        noise.correction =
            PositiveOrAuto(reader, value["correction"], Child(key, "correction"), true);
      }
    }
    spec->input_noise[input] = noise;
  }
  if (spec->input_noise.empty()) reader.Fail(node, path, "no input listed");
}

}  // namespace vesselid

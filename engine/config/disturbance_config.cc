#include "engine/config/disturbance_config.h"

#include <cmath>

namespace vesselid {
namespace {

// `auto` (NaN) or a positive number.
double PositiveOrAuto(const YamlReader& reader, const YAML::Node& node, const std::string& key) {
  if (node.IsScalar() && node.Scalar() == "auto") return std::nan("");
  const double value = reader.Double(node, key);
  if (!(value > 0.0)) reader.Fail(node, key, "must be > 0 (or auto)");
  return value;
}

}  // namespace

void ReadDisturbance(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                     const ModelInfo& info, DisturbanceSpec* spec) {
  if (node.IsScalar()) {  // noise: output_error | filter_error | auto
    const std::string text = reader.String(node, path);
    if (!StringToDisturbanceMethod(text, &spec->method)) {
      reader.Fail(node, path, "unknown method '" + text + "' (output_error, filter_error, auto)");
    }
    return;
  }
  if (!node.IsMap()) reader.Fail(node, path, "expected output_error, filter_error, auto or a map");
  reader.CheckMap(node, path,
                  {"method", "angles", "measurement", "process", "wave", "bias",
                   "prediction_steps", "gain"});
  spec->method = DisturbanceSpec::Method::kFilterError;
  if (const YAML::Node n = node["method"]) {
    const std::string text = reader.String(n, Child(path, "method"));
    if (!StringToDisturbanceMethod(text, &spec->method)) {
      reader.Fail(n, Child(path, "method"),
                  "unknown method '" + text + "' (output_error, filter_error, auto)");
    }
  }
  double angle = 1.0;
  if (const YAML::Node n = node["angles"]) {
    const std::string text = reader.String(n, Child(path, "angles"));
    if (text == "deg")
      angle = M_PI / 180.0;
    else if (text != "rad")
      reader.Fail(n, Child(path, "angles"), "expected rad or deg");
  }
  // Sigmas of angle outputs in the section's angle unit.
  auto output_scale = [&](int j) {
    return j >= 0 && j < static_cast<int>(info.angle_outputs.size()) && info.angle_outputs[j]
               ? angle
               : 1.0;
  };
  auto output_of = [&](const YAML::Node& name, const std::string& key) {
    const std::string output = reader.KeyName(name, key);
    if (info.OutputIndex(output) < 0) {
      reader.Fail(name, Child(key, output),
                  "unknown output '" + output + "' (model " + info.name + " has " +
                      JoinNames(info.outputs) + ")");
    }
    return output;
  };
  if (const YAML::Node m = node["measurement"]) {
    const std::string key = Child(path, "measurement");
    reader.CheckMap(m, key, info.outputs);
    for (const auto& item : m) {
      DisturbanceSpec::Measurement noise;
      noise.output = output_of(item.first, key);
      const std::string at = Child(key, noise.output);
      const double scale = output_scale(info.OutputIndex(noise.output));
      const YAML::Node& value = item.second;
      std::string type;
      if (value.IsScalar()) {
        type = reader.String(value, at);
      } else {
        reader.CheckMap(value, at, {"type", "sigma", "tau", "white"});
        type = value["type"] ? reader.String(value["type"], Child(at, "type")) : "white";
        if (value["sigma"]) noise.sigma = PositiveOrAuto(reader, value["sigma"], Child(at, "sigma")) * scale;
        if (value["tau"]) noise.tau = PositiveOrAuto(reader, value["tau"], Child(at, "tau"));
        if (value["white"]) noise.white_too = reader.Bool(value["white"], Child(at, "white"));
      }
      if (type == "white") {
        noise.type = DisturbanceSpec::Measurement::Type::kWhite;
      } else if (type == "ar1") {
        noise.type = DisturbanceSpec::Measurement::Type::kAr1;
      } else {
        reader.Fail(value, at, "unknown measurement noise '" + type + "' (white, ar1)");
      }
      spec->measurement.push_back(noise);
    }
  }
  if (const YAML::Node p = node["process"]) {
    const std::string key = Child(path, "process");
    reader.CheckMap(p, key, info.states);
    for (const auto& item : p) {
      DisturbanceSpec::Process noise;
      noise.state = reader.KeyName(item.first, key);
      if (info.StateIndex(noise.state) < 0) {
        reader.Fail(item.first, Child(key, noise.state),
                    "unknown state '" + noise.state + "' (model " + info.name + " has " +
                        JoinNames(info.states) + ")");
      }
      noise.q = PositiveOrAuto(reader, item.second, Child(key, noise.state));
      spec->process.push_back(noise);
    }
  }
  if (const YAML::Node w = node["wave"]) {
    const std::string key = Child(path, "wave");
    reader.CheckMap(w, key, info.outputs);
    for (const auto& item : w) {
      DisturbanceSpec::Wave wave;
      wave.output = output_of(item.first, key);
      const std::string at = Child(key, wave.output);
      const YAML::Node& value = item.second;
      if (value.IsScalar()) {
        if (value.Scalar() != "auto") reader.Fail(value, at, "expected auto or {omega, zeta, sigma}");
      } else {
        reader.CheckMap(value, at, {"omega", "zeta", "sigma"});
        if (value["omega"]) wave.omega = PositiveOrAuto(reader, value["omega"], Child(at, "omega"));
        if (std::isnan(wave.omega)) wave.omega = 0.8;
        if (value["zeta"]) {
          wave.zeta = reader.Double(value["zeta"], Child(at, "zeta"));
          if (!(wave.zeta > 0.0 && wave.zeta < 1.0)) {
            reader.Fail(value["zeta"], Child(at, "zeta"), "must be in (0, 1)");
          }
        }
        if (value["sigma"]) {
          wave.sigma = PositiveOrAuto(reader, value["sigma"], Child(at, "sigma")) *
                       output_scale(info.OutputIndex(wave.output));
        }
      }
      spec->wave.push_back(wave);
    }
  }
  if (const YAML::Node b = node["bias"]) {
    const std::string key = Child(path, "bias");
    reader.CheckMap(b, key, info.outputs);
    for (const auto& item : b) {
      DisturbanceSpec::Bias bias;
      bias.output = output_of(item.first, key);
      const std::string at = Child(key, bias.output);
      const YAML::Node& value = item.second;
      const double scale = output_scale(info.OutputIndex(bias.output));
      if (value.IsScalar()) {
        if (value.Scalar() != "auto") reader.Fail(value, at, "expected auto or {q, initial_sd}");
      } else {
        reader.CheckMap(value, at, {"q", "initial_sd"});
        if (value["q"]) bias.q = PositiveOrAuto(reader, value["q"], Child(at, "q")) * scale * scale;
        if (value["initial_sd"]) {
          bias.initial_sd =
              PositiveOrAuto(reader, value["initial_sd"], Child(at, "initial_sd")) * scale;
        }
      }
      spec->bias.push_back(bias);
    }
  }
  // The parts are the filter's: auto chooses its own candidates (disturbance_choice.h), and
  // output error has none; neither would use them.
  if (spec->method != DisturbanceSpec::Method::kFilterError) {
    for (const char* part : {"measurement", "process", "wave", "bias"}) {
      if (const YAML::Node n = node[part]) {
        reader.Fail(n, Child(path, part),
                    std::string("not used under method ") +
                        DisturbanceMethodToString(spec->method) +
                        (spec->method == DisturbanceSpec::Method::kAuto
                             ? ", which chooses the disturbance model itself; give the parts "
                               "with method filter_error"
                             : "; give the parts with method filter_error"));
      }
    }
  }
  if (const YAML::Node g = node["gain"]) {
    const std::string text = reader.String(g, Child(path, "gain"));
    if (text == "auto")
      spec->steady_gain = true;
    else if (text == "time_varying")
      spec->steady_gain = false;
    else
      reader.Fail(g, Child(path, "gain"), "expected auto or time_varying");
  }
  if (const YAML::Node k = node["prediction_steps"]) {
    spec->prediction_steps = reader.Int(k, Child(path, "prediction_steps"));
    if (spec->prediction_steps < 1) reader.Fail(k, Child(path, "prediction_steps"), "must be >= 1");
  }
}

}  // namespace vesselid

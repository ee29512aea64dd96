#include "engine/design/design_config.h"

#include <cmath>

#include "engine/config/yaml_reader.h"
#include "engine/design/design_names.h"

namespace vesselid {
namespace {

DesignInput ReadInput(const YamlReader& reader, const YAML::Node& node, const std::string& name,
                      const std::string& key) {
  reader.CheckMap(
      node, key,
      {"family", "lower", "upper", "rate", "value", "hold", "periods", "headings", "degrees"});
  DesignInput in;
  in.name = name;
  if (!node["family"])
    reader.Fail(node, key, "missing key 'family' (steps, multisine, zigzag, fixed)");
  const std::string family = reader.String(node["family"], Child(key, "family"));
  if (family == "steps") {
    in.family = DesignInput::Family::kSteps;
  } else if (family == "multisine") {
    in.family = DesignInput::Family::kMultisine;
  } else if (family == "zigzag") {
    in.family = DesignInput::Family::kZigzag;
  } else if (family == "fixed") {
    in.family = DesignInput::Family::kFixed;
  } else {
    reader.Fail(node["family"], Child(key, "family"),
                "unknown family '" + family + "' (steps, multisine, zigzag, fixed)");
  }
  reader.Read(node, key, "degrees", &in.degrees);
  const double unit = in.degrees ? kDesignDegree : 1.0;
  const bool fixed = in.family == DesignInput::Family::kFixed;
  if (!fixed && (!node["lower"] || !node["upper"])) {
    reader.Fail(node, key, "needs lower and upper (the input's limits)");
  }
  if (fixed && !node["value"]) reader.Fail(node, key, "a fixed input needs its value");
  reader.Read(node, key, "lower", &in.lower);
  reader.Read(node, key, "upper", &in.upper);
  reader.Read(node, key, "rate", &in.rate);
  if (!fixed && !(in.lower < in.upper)) reader.Fail(node, key, "needs lower < upper");
  if (in.rate < 0.0) reader.Fail(node["rate"], Child(key, "rate"), "must be >= 0 (0: no limit)");
  in.value = in.lower <= 0.0 && 0.0 <= in.upper ? 0.0 : 0.5 * (in.lower + in.upper);
  if (fixed) in.value = 0.0;
  reader.Read(node, key, "value", &in.value);
  if (!fixed && (in.value < in.lower || in.value > in.upper)) {
    reader.Fail(node["value"], Child(key, "value"), "outside [lower, upper]");
  }
  reader.Read(node, key, "hold", &in.hold);
  if (in.hold < 0.0) reader.Fail(node["hold"], Child(key, "hold"), "must be > 0");
  if (node["periods"]) {
    in.periods = reader.Doubles(node["periods"], Child(key, "periods"));
    for (double p : in.periods) {
      if (!(p > 0.0)) reader.Fail(node["periods"], Child(key, "periods"), "periods must be > 0");
    }
  }
  if (in.family == DesignInput::Family::kZigzag) {
    std::vector<double> h = {5.0, 30.0};
    if (node["headings"]) h = reader.Doubles(node["headings"], Child(key, "headings"));
    if (h.size() != 2 || !(h[0] > 0.0 && h[0] <= h[1])) {
      reader.Fail(node["headings"], Child(key, "headings"),
                  "[lowest, highest], 0 < lowest <= highest");
    }
    // Switch headings in degrees, as a zigzag is named (10/10, 20/20), whatever the rudder's unit.
    in.headings = {h[0] * kDesignDegree, h[1] * kDesignDegree};
  }
  in.lower *= unit;
  in.upper *= unit;
  in.rate *= unit;
  in.value *= unit;
  return in;
}

}  // namespace

bool LoadDesign(const std::string& path, DesignOptions* options, std::string* error,
                const std::string& text) {
  YamlReader reader = text.empty() ? YamlReader(path) : YamlReader(path, text);
  try {
    const YAML::Node root = reader.Load();
    const YAML::Node d = root["design"];
    if (!d) reader.Fail(root, "design", "missing: the config has no design section");
    reader.CheckMap(d, "design",
                    {"duration", "sample_time", "criterion", "inputs", "box", "noise", "noise_deg",
                     "initial_state", "settle", "free_initial_states", "search", "robust"});
    DesignOptions out;
    if (const YAML::Node model = root["model"]; model && model.IsMap() && model["family"]) {
      out.family = reader.String(model["family"], "model.family");
    }
    if (const YAML::Node n = d["duration"]) {
      if (n.IsScalar() && n.Scalar() == "zigzag_20_20") {
        out.duration = 0.0;
      } else {
        out.duration = reader.Double(n, "design.duration");
        if (!(out.duration > 0.0))
          reader.Fail(n, "design.duration", "must be > 0 s, or zigzag_20_20");
      }
    }
    reader.Read(d, "design", "sample_time", &out.sample_time);
    if (out.sample_time < 0.0) reader.Fail(d["sample_time"], "design.sample_time", "must be > 0");
    if (const YAML::Node c = d["criterion"]) {
      if (c.IsMap()) {
        reader.CheckMap(c, "design.criterion", {"parameter"});
        out.criterion = DesignCriterion::kParameter;
        out.parameter = reader.String(c["parameter"], "design.criterion.parameter");
      } else {
        const std::string text = reader.String(c, "design.criterion");
        if (text == "D") {
          out.criterion = DesignCriterion::kD;
        } else if (text == "A") {
          out.criterion = DesignCriterion::kA;
        } else if (text == "E") {
          out.criterion = DesignCriterion::kE;
        } else {
          reader.Fail(c, "design.criterion", "D, A, E or {parameter: <name>}");
        }
      }
    }
    if (const YAML::Node box = d["box"]) {
      if (!box.IsMap()) reader.Fail(box, "design.box", "a map of outputs to [lower, upper]");
      for (const auto& item : box) {
        const std::string name = reader.KeyName(item.first, "design.box");
        const std::vector<double> range = reader.Doubles(item.second, "design.box." + name);
        if (range.size() != 2 || !(range[0] < 0.0 && 0.0 < range[1])) {
          reader.Fail(item.second, "design.box." + name,
                      "[lower, upper] around the start (lower < 0 < upper)");
        }
        out.box[name] = {range[0], range[1]};
      }
    }
    if (d["noise"]) out.noise = reader.DoubleMap(d["noise"], "design.noise");
    if (d["noise_deg"]) {
      for (const auto& [name, value] : reader.DoubleMap(d["noise_deg"], "design.noise_deg")) {
        out.noise[name] = value * kDesignDegree;
      }
    }
    for (const auto& [name, value] : out.noise) {
      if (!(value > 0.0)) reader.Fail(d, "design.noise." + name, "must be > 0");
    }
    if (d["initial_state"])
      out.initial_state = reader.DoubleMap(d["initial_state"], "design.initial_state");
    reader.Read(d, "design", "settle", &out.settle);
    if (out.settle < 0.0) reader.Fail(d["settle"], "design.settle", "must be >= 0 s");
    if (d["free_initial_states"]) {
      out.free_initial_states =
          reader.Strings(d["free_initial_states"], "design.free_initial_states");
      out.free_initial_states_given = true;
    }
    if (const YAML::Node s = d["search"]) {
      reader.CheckMap(s, "design.search",
                      {"starts", "refined", "max_evaluations", "seed", "threads"});
      reader.Read(s, "design.search", "starts", &out.starts);
      reader.Read(s, "design.search", "refined", &out.refined);
      reader.Read(s, "design.search", "max_evaluations", &out.max_evaluations);
      int seed = static_cast<int>(out.seed);
      reader.Read(s, "design.search", "seed", &seed);
      out.seed = static_cast<unsigned>(seed);
      reader.Read(s, "design.search", "threads", &out.threads);
      if (out.starts < 1 || out.refined < 1 || out.max_evaluations < 1 || out.threads < 0) {
        reader.Fail(s, "design.search", "starts, refined, max_evaluations >= 1; threads >= 0");
      }
    }
    if (const YAML::Node r = d["robust"]) {
      reader.CheckMap(r, "design.robust", {"members"});
      reader.Read(r, "design.robust", "members", &out.ensemble_members);
      if (out.ensemble_members < 2) reader.Fail(r, "design.robust.members", "must be >= 2");
    }
    // The inputs last: a section's own keys are checked whatever the inputs hold.
    const YAML::Node inputs = d["inputs"];
    if (!inputs || !inputs.IsMap() || inputs.size() == 0) {
      reader.Fail(inputs ? inputs : d, "design.inputs", "a map of the model's inputs to plan");
    }
    for (const auto& item : inputs) {
      const std::string name = reader.KeyName(item.first, "design.inputs");
      out.inputs.push_back(ReadInput(reader, item.second, name, "design.inputs." + name));
    }
    *options = std::move(out);
    return true;
  } catch (const ConfigError& e) {
    *error = e.what();
    return false;
  }
}

}  // namespace vesselid

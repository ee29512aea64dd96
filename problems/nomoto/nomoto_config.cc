#include "problems/nomoto/nomoto_config.h"

#include <filesystem>

#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"

namespace vesselid::nomoto {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = M_PI / 180.0;

std::unique_ptr<ModelHandle> MakeModel(const YamlReader& reader, const YAML::Node& model,
                                       const std::string& path) {
  reader.CheckMap(model, path, {"family", "type"});
  if (!model["type"])
    reader.Fail(model, Child(path, "type"), "missing (first_order, second_order, norrbin)");
  const std::string type = reader.String(model["type"], Child(path, "type"));
  if (type == "first_order") return MakeFirstOrderHandle();
  if (type == "second_order") return MakeSecondOrderHandle();
  if (type == "norrbin") return MakeNorrbinHandle();
  reader.Fail(model["type"], Child(path, "type"),
              "unknown Nomoto model '" + type + "' (first_order, second_order, norrbin)");
}

Excitation ReadExcitation(const YamlReader& reader, const YAML::Node& node,
                          const std::string& path) {
  reader.CheckMap(node, path,
                  {"type", "amplitude_deg", "period", "periods", "rudder_deg", "heading_deg"});
  Excitation e;
  const std::string type = node["type"] ? reader.String(node["type"], Child(path, "type")) : "sine";
  if (type == "sine") {
    e.type = Excitation::Type::kSine;
  } else if (type == "multisine") {
    e.type = Excitation::Type::kMultisine;
  } else if (type == "zigzag") {
    e.type = Excitation::Type::kZigzag;
  } else {
    reader.Fail(node["type"], Child(path, "type"),
                "unknown excitation '" + type + "' (sine, multisine, zigzag)");
  }
  double amplitude = 0.0, rudder = 0.0, heading = 0.0;
  reader.Read(node, path, "amplitude_deg", &amplitude);
  reader.Read(node, path, "rudder_deg", &rudder);
  reader.Read(node, path, "heading_deg", &heading);
  e.amplitude = amplitude * kDegree;
  e.zigzag_rudder = rudder * kDegree;
  e.zigzag_heading = heading * kDegree;
  if (node["period"]) e.periods = {reader.Double(node["period"], Child(path, "period"))};
  if (node["periods"]) e.periods = reader.Doubles(node["periods"], Child(path, "periods"));
  return e;
}

bool Simulate(const YamlReader& reader, const YAML::Node& simulation, const ModelHandle& model,
              const std::string& out_dir, bool check_only, std::string* error) {
  const std::string path = "simulation";
  if (!simulation) reader.Fail(simulation, path, "missing: the config has no simulation section");
  reader.CheckMap(simulation, path,
                  {"truth", "steering_gear", "sample_time", "substeps", "experiments"});
  const ModelInfo& info = model.info();
  std::vector<double> truth = info.parameter_defaults;
  if (!simulation["truth"]) reader.Fail(simulation, Child(path, "truth"), "missing");
  reader.CheckMap(simulation["truth"], Child(path, "truth"), info.parameters);
  for (const auto& item : simulation["truth"]) {
    const std::string name = item.first.as<std::string>();
    truth[info.ParameterIndex(name)] =
        reader.Double(item.second, Child(Child(path, "truth"), name));
  }
  ClosedLoopOptions base;
  if (const YAML::Node gear = simulation["steering_gear"]) {
    const std::string key = Child(path, "steering_gear");
    reader.CheckMap(gear, key, {"Tm", "kp", "rudder_limit_deg"});
    reader.Read(gear, key, "Tm", &base.steering_time_constant);
    reader.Read(gear, key, "kp", &base.controller_gain);
    double limit = base.rudder_limit / kDegree;
    reader.Read(gear, key, "rudder_limit_deg", &limit);
    base.rudder_limit = limit * kDegree;
  }
  reader.Read(simulation, path, "sample_time", &base.sample_time);
  reader.Read(simulation, path, "substeps", &base.substeps);
  const YAML::Node experiments = simulation["experiments"];
  if (!experiments) reader.Fail(simulation, Child(path, "experiments"), "missing");
  reader.CheckSequence(experiments, Child(path, "experiments"));

  // Parse everything first so that a config error leaves no file behind.
  std::vector<std::pair<std::string, ClosedLoopOptions>> runs;
  for (size_t i = 0; i < experiments.size(); ++i) {
    const YAML::Node node = experiments[i];
    const std::string key = Child(Child(path, "experiments"), i);
    reader.CheckMap(node, key, {"file", "duration", "excitation", "noise", "seed"});
    if (!node["file"]) reader.Fail(node, key, "missing key 'file'");
    ClosedLoopOptions options = base;
    reader.Read(node, key, "duration", &options.duration);
    if (!node["excitation"]) reader.Fail(node, key, "missing key 'excitation'");
    options.excitation = ReadExcitation(reader, node["excitation"], Child(key, "excitation"));
    if (const YAML::Node noise = node["noise"]) {
      reader.CheckMap(noise, Child(key, "noise"), {"rudder_deg", "heading_deg"});
      double rudder = 0.0, heading = 0.0;
      reader.Read(noise, Child(key, "noise"), "rudder_deg", &rudder);
      reader.Read(noise, Child(key, "noise"), "heading_deg", &heading);
      options.rudder_noise = rudder * kDegree;
      options.heading_noise = heading * kDegree;
    }
    int seed = static_cast<int>(i + 1);
    reader.Read(node, key, "seed", &seed);
    options.seed = static_cast<unsigned>(seed);
    std::string problem;
    if (!options.IsValid(&problem)) reader.Fail(node, key, problem);
    reader.CheckLimit(node["duration"], Child(key, "duration"),
                      options.duration / options.sample_time * options.substeps,
                      reader.limits().integration_steps, "limits.integration_steps");
    runs.emplace_back(reader.String(node["file"], Child(key, "file")), options);
  }
  if (check_only) return true;
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) {
    *error = out_dir + ": cannot create folder: " + ec.message();
    return false;
  }
  for (const auto& [file, options] : runs) {
    Trajectory trajectory;
    if (!SimulateClosedLoop(model, truth, options, &trajectory, error)) return false;
    const std::string target = (fs::path(out_dir) / file).string();
    if (!WriteTrajectoryCsv(target, trajectory, error)) return false;
  }
  return true;
}

}  // namespace

ModelFamily NomotoFamily() {
  return {"nomoto", "Nomoto steering models (first order, second order, Norrbin)", MakeModel,
          Simulate};
}

}  // namespace vesselid::nomoto

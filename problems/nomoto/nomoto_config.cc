#include "problems/nomoto/nomoto_config.h"

#include <cmath>
#include <filesystem>

#include "engine/base/file_name.h"
#include "engine/config/family_simulation.h"
#include "engine/data/trajectory.h"
#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"

namespace vesselid::nomoto {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = M_PI / 180.0;

constexpr char kTypes[] =
    "first_order, second_order, norrbin, first_order_n1, norrbin_n1, second_order_rates";

std::unique_ptr<ModelHandle> MakeModel(const YamlReader& reader, const YAML::Node& model,
                                       const std::string& path) {
  reader.CheckMap(model, path, {"family", "type", "length"});
  if (!model["type"]) {
    reader.Fail(model, Child(path, "type"), std::string("missing (") + kTypes + ")");
  }
  const std::string type = reader.String(model["type"], Child(path, "type"));
  const bool n1_form = type == "first_order_n1" || type == "norrbin_n1";
  double length = 0.0;
  if (model["length"]) {
    if (!n1_form) {
      reader.Fail(model["length"], Child(path, "length"),
                  "only the n1-form models (first_order_n1, norrbin_n1) take a ship length "
                  "and a speed input");
    }
    length = reader.Double(model["length"], Child(path, "length"));
    if (!(length > 0.0)) reader.Fail(model["length"], Child(path, "length"), "must be > 0 [m]");
  }
  if (type == "first_order") return MakeFirstOrderHandle();
  if (type == "second_order") return MakeSecondOrderHandle();
  if (type == "norrbin") return MakeNorrbinHandle();
  if (n1_form) return MakeN1FormHandle(type == "norrbin_n1", length);
  if (type == "second_order_rates") return MakeSecondOrderRatesHandle();
  reader.Fail(model["type"], Child(path, "type"),
              "unknown Nomoto model '" + type + "' (" + kTypes + ")");
}

// A planned rudder command (`vesselid design`'s planned_input.csv): `file` relative to the
// config's folder, `column` (default delta_deg; a name ending in _deg is in degrees).
void ReadPlannedCommand(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                        Excitation* e) {
  if (!node["file"]) reader.Fail(node, path, "a planned excitation needs its file");
  std::string file = reader.String(node["file"], Child(path, "file"));
  if (std::filesystem::path(file).is_relative()) {
    file = (std::filesystem::path(reader.file()).parent_path() / file).string();
  }
  std::string column = "delta_deg";
  reader.Read(node, path, "column", &column);
  Trajectory table;
  std::string error;
  if (!ReadTrajectoryCsv(file, &table, &error))
    reader.Fail(node["file"], Child(path, "file"), error);
  const int c = table.Find(column);
  if (c < 0) reader.Fail(node, Child(path, "column"), file + " has no column '" + column + "'");
  const bool degrees = column.size() > 4 && column.compare(column.size() - 4, 4, "_deg") == 0;
  for (size_t k = 0; k < table.t.size(); ++k) {
    const double value = table.columns[c][k];
    if (!std::isfinite(value)) continue;
    e->planned_t.push_back(table.t[k]);
    e->planned_delta.push_back(degrees ? value * kDegree : value);
  }
  if (e->planned_t.size() < 2) reader.Fail(node["file"], Child(path, "file"), "needs two samples");
}

Excitation ReadExcitation(const YamlReader& reader, const YAML::Node& node,
                          const std::string& path) {
  reader.CheckMap(node, path,
                  {"type", "amplitude_deg", "period", "periods", "rudder_deg", "heading_deg",
                   "first", "file", "column"});
  Excitation e;
  const std::string type = node["type"] ? reader.String(node["type"], Child(path, "type")) : "sine";
  if (type == "sine") {
    e.type = Excitation::Type::kSine;
  } else if (type == "multisine") {
    e.type = Excitation::Type::kMultisine;
  } else if (type == "zigzag") {
    e.type = Excitation::Type::kZigzag;
  } else if (type == "planned") {
    e.type = Excitation::Type::kPlanned;
    ReadPlannedCommand(reader, node, path, &e);
  } else {
    reader.Fail(node["type"], Child(path, "type"),
                "unknown excitation '" + type + "' (sine, multisine, zigzag, planned)");
  }
  if (e.type != Excitation::Type::kPlanned && (node["file"] || node["column"])) {
    reader.Fail(node, path, "file and column belong to a planned excitation");
  }
  double amplitude = 0.0, rudder = 0.0, heading = 0.0;
  reader.Read(node, path, "amplitude_deg", &amplitude);
  reader.Read(node, path, "rudder_deg", &rudder);
  reader.Read(node, path, "heading_deg", &heading);
  e.amplitude = amplitude * kDegree;
  e.zigzag_rudder = rudder * kDegree;
  e.zigzag_heading = heading * kDegree;
  if (node["first"]) {
    if (e.type != Excitation::Type::kZigzag) {
      reader.Fail(node["first"], Child(path, "first"), "only a zigzag has a first side");
    }
    const std::string first = reader.String(node["first"], Child(path, "first"));
    if (first != "port" && first != "starboard") {
      reader.Fail(node["first"], Child(path, "first"), "'" + first + "': port or starboard");
    }
    e.zigzag_first = first == "port" ? -1.0 : 1.0;
  }
  if (node["period"]) e.periods = {reader.Double(node["period"], Child(path, "period"))};
  if (node["periods"]) e.periods = reader.Doubles(node["periods"], Child(path, "periods"));
  return e;
}

bool Simulate(const YamlReader& reader, const YAML::Node& simulation, const ModelHandle& model,
              const std::string& out_dir, bool check_only, std::string* error) {
  const std::string path = "simulation";
  if (!simulation) reader.Fail(simulation, path, "missing: the config has no simulation section");
  reader.CheckMap(simulation, path,
                  {"truth", "steering_gear", "sample_time", "substeps", "experiments", "degrees"});
  const ModelInfo& info = model.info();
  if (!simulation["truth"]) reader.Fail(simulation, Child(path, "truth"), "missing");
  const std::vector<double> truth =
      ReadTruth(reader, simulation["truth"], Child(path, "truth"), info, info.parameter_defaults);
  ClosedLoopOptions base;
  if (const YAML::Node gear = simulation["steering_gear"]) {
    const std::string key = Child(path, "steering_gear");
    reader.CheckMap(gear, key, {"Tm", "kp", "rudder_limit_deg", "rate_limit_deg_s"});
    reader.Read(gear, key, "Tm", &base.steering_time_constant);
    reader.Read(gear, key, "kp", &base.controller_gain);
    double limit = base.rudder_limit / kDegree;
    reader.Read(gear, key, "rudder_limit_deg", &limit);
    base.rudder_limit = limit * kDegree;
    double rate = 0.0;
    reader.Read(gear, key, "rate_limit_deg_s", &rate);
    base.rudder_rate = rate * kDegree;
  }
  bool degrees = false;
  reader.Read(simulation, path, "degrees", &degrees);
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
    reader.CheckMap(node, key,
                    {"file", "duration", "excitation", "noise", "seed", "speed", "rudder_bias_deg",
                     "disturbance"});
    if (!node["file"]) reader.Fail(node, key, "missing key 'file'");
    ClosedLoopOptions options = base;
    reader.Read(node, key, "duration", &options.duration);
    if (!node["excitation"]) reader.Fail(node, key, "missing key 'excitation'");
    options.excitation = ReadExcitation(reader, node["excitation"], Child(key, "excitation"));
    if (const YAML::Node noise = node["noise"]) {
      reader.CheckMap(noise, Child(key, "noise"),
                      {"rudder_deg", "heading_deg", "heading_resolution_deg"});
      double rudder = 0.0, heading = 0.0, resolution = 0.0;
      reader.Read(noise, Child(key, "noise"), "rudder_deg", &rudder);
      reader.Read(noise, Child(key, "noise"), "heading_deg", &heading);
      reader.Read(noise, Child(key, "noise"), "heading_resolution_deg", &resolution);
      options.rudder_noise = rudder * kDegree;
      options.heading_noise = heading * kDegree;
      options.heading_resolution = resolution * kDegree;
    }
    double bias = 0.0;
    reader.Read(node, key, "rudder_bias_deg", &bias);
    options.rudder_bias = bias * kDegree;
    reader.Read(node, key, "speed", &options.speed);
    const bool takes_speed = info.InputIndex("U") >= 0;
    if (takes_speed != (options.speed > 0)) {
      reader.Fail(node, Child(key, "speed"),
                  takes_speed
                      ? "model " + info.name + " takes a speed input: give a speed > 0 [m/s]"
                      : "model " + info.name + " takes no speed input");
    }
    if (const YAML::Node disturbance = node["disturbance"]) {
      const std::string dkey = Child(key, "disturbance");
      reader.CheckMap(disturbance, dkey, {"rudder_deg", "period"});
      double amplitude = 0.0;
      reader.Read(disturbance, dkey, "rudder_deg", &amplitude);
      options.disturbance_amplitude = amplitude * kDegree;
      reader.Read(disturbance, dkey, "period", &options.disturbance_period);
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
  if (!CreateSimulationFolder(out_dir, error)) return false;
  for (const auto& [file, options] : runs) {
    Trajectory trajectory;
    if (!SimulateClosedLoop(model, truth, options, &trajectory, error)) return false;
    if (degrees) {  // every angle and the yaw rate in degrees (deg/s), as many logs have them
      for (size_t c = 0; c < trajectory.names.size(); ++c) {
        if (trajectory.names[c] == "U") continue;
        for (double& value : trajectory.columns[c]) value /= kDegree;
      }
    }
    *error = OutputFileNameProblem(file, "simulation.experiments[].file");
    if (!error->empty()) return false;
    const std::string target = (fs::path(out_dir) / file).string();
    if (!WriteTrajectoryCsv(target, trajectory, error)) return false;
  }
  return true;
}

}  // namespace

ModelFamily NomotoFamily() {
  return {"nomoto",
          "Nomoto steering models (first order, second order, Norrbin; n1-forms and the "
          "second-order rates form for course-unstable ships)",
          MakeModel, Simulate};
}

}  // namespace vesselid::nomoto

#include "problems/mmg/mmg_config.h"

#include <filesystem>

#include "engine/base/file_name.h"
#include "engine/config/family_simulation.h"
#include "problems/mmg/campaign.h"
#include "problems/mmg/handles.h"

namespace vesselid::mmg {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = M_PI / 180.0;

//   model: {family: mmg, length: 7.0, draft: 0.455, displacement: 3.2724,
//           centre_of_gravity: 0.245, radius_of_gyration: 0.25, propeller_diameter: 0.216,
//           rudder_area: 0.0539, rudder_height: 0.345, rudder_position: -0.5,
//           water_density: 1000}          (defaults: the KVLCC2's 7 m model)
std::unique_ptr<ModelHandle> MakeModel(const YamlReader& reader, const YAML::Node& node,
                                       const std::string& path) {
  reader.CheckMap(
      node, path,
      {"family", "length", "draft", "displacement", "centre_of_gravity", "radius_of_gyration",
       "propeller_diameter", "rudder_area", "rudder_height", "rudder_position", "water_density"});
  Ship ship;
  reader.Read(node, path, "length", &ship.length);
  reader.Read(node, path, "draft", &ship.draft);
  reader.Read(node, path, "displacement", &ship.displacement);
  reader.Read(node, path, "centre_of_gravity", &ship.centre_of_gravity);
  reader.Read(node, path, "radius_of_gyration", &ship.radius_of_gyration);
  reader.Read(node, path, "propeller_diameter", &ship.propeller_diameter);
  reader.Read(node, path, "rudder_area", &ship.rudder_area);
  reader.Read(node, path, "rudder_height", &ship.rudder_height);
  reader.Read(node, path, "rudder_position", &ship.rudder_position);
  reader.Read(node, path, "water_density", &ship.water_density);
  std::string problem;
  if (!ship.IsValid(&problem)) reader.Fail(node, path, problem);
  return MakeMmgHandle(ship);
}

CampaignRun ReadRun(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                    CampaignRun run, int index) {
  reader.CheckMap(node, key,
                  {"file", "type", "rudder_deg", "heading_deg", "first", "duration",
                   "propeller_rate", "rudder_bias_deg", "disturbance", "noise", "seed"});
  if (!node["file"]) reader.Fail(node, key, "missing key 'file'");
  const std::string type = node["type"] ? reader.String(node["type"], Child(key, "type")) : "";
  if (type == "zigzag") {
    run.type = CampaignRun::Type::kZigzag;
  } else if (type == "turning") {
    run.type = CampaignRun::Type::kTurning;
    if (node["heading_deg"]) {
      reader.Fail(node["heading_deg"], Child(key, "heading_deg"), "only a zigzag has one");
    }
  } else {
    reader.Fail(node["type"] ? node["type"] : node, Child(key, "type"),
                (type.empty() ? std::string("missing") : "unknown run type '" + type + "'") +
                    " (zigzag, turning)");
  }
  ReadDegrees(reader, node, key, "rudder_deg", &run.rudder);
  ReadDegrees(reader, node, key, "heading_deg", &run.heading);
  if (node["first"]) {
    const std::string first = reader.String(node["first"], Child(key, "first"));
    if (first != "port" && first != "starboard") {
      reader.Fail(node["first"], Child(key, "first"), "'" + first + "': port or starboard");
    }
    run.first = first == "port" ? -1.0 : 1.0;
  }
  reader.Read(node, key, "duration", &run.duration);
  reader.Read(node, key, "propeller_rate", &run.propeller_rate);
  ReadDegrees(reader, node, key, "rudder_bias_deg", &run.rudder_bias);
  if (const YAML::Node d = node["disturbance"]) {
    const std::string dkey = Child(key, "disturbance");
    reader.CheckMap(d, dkey, {"rudder_deg", "period"});
    ReadDegrees(reader, d, dkey, "rudder_deg", &run.disturbance_amplitude);
    reader.Read(d, dkey, "period", &run.disturbance_period);
  }
  if (const YAML::Node noise = node["noise"]) {
    const std::string nkey = Child(key, "noise");
    reader.CheckMap(noise, nkey, {"position", "heading_deg", "speed", "rudder_deg"});
    reader.Read(noise, nkey, "position", &run.position_noise);
    ReadDegrees(reader, noise, nkey, "heading_deg", &run.heading_noise);
    reader.Read(noise, nkey, "speed", &run.speed_noise);
    ReadDegrees(reader, noise, nkey, "rudder_deg", &run.rudder_noise);
  }
  int seed = index + 1;
  reader.Read(node, key, "seed", &seed);
  run.seed = static_cast<unsigned>(seed);
  std::string problem;
  if (!run.IsValid(&problem)) reader.Fail(node, key, problem);
  reader.CheckLimit(node["duration"] ? node["duration"] : node, Child(key, "duration"),
                    run.duration / run.sample_time * run.substeps,
                    reader.limits().integration_steps, "limits.integration_steps");
  return run;
}

//   simulation: {truth: {Y_v: -0.315}, sample_time: 0.1, substeps: 4, degrees: true,
//                steering_gear: {Tm: 0.1, rate_limit_deg_s: 15.8},
//                experiments: [{file, type: zigzag | turning, rudder_deg, heading_deg,
//                               first: starboard | port, duration, propeller_rate,
//                               rudder_bias_deg, disturbance: {rudder_deg, period},
//                               noise: {position, heading_deg, speed, rudder_deg}, seed}]}
bool Simulate(const YamlReader& reader, const YAML::Node& simulation, const ModelHandle& model,
              const std::string& out_dir, bool check_only, std::string* error) {
  const std::string path = "simulation";
  if (!simulation) reader.Fail(simulation, path, "missing: the config has no simulation section");
  reader.CheckMap(simulation, path,
                  {"truth", "sample_time", "substeps", "degrees", "steering_gear", "experiments"});
  const ModelInfo& info = model.info();
  const std::vector<double> truth =
      ReadTruth(reader, simulation["truth"], Child(path, "truth"), info, info.parameter_defaults);
  CampaignRun base;
  reader.Read(simulation, path, "sample_time", &base.sample_time);
  reader.Read(simulation, path, "substeps", &base.substeps);
  bool degrees = false;
  reader.Read(simulation, path, "degrees", &degrees);
  if (const YAML::Node gear = simulation["steering_gear"]) {
    const std::string key = Child(path, "steering_gear");
    reader.CheckMap(gear, key, {"Tm", "rate_limit_deg_s"});
    reader.Read(gear, key, "Tm", &base.steering_time_constant);
    ReadDegrees(reader, gear, key, "rate_limit_deg_s", &base.rudder_rate);
  }
  const YAML::Node experiments = simulation["experiments"];
  if (!experiments) reader.Fail(simulation, Child(path, "experiments"), "missing");
  reader.CheckSequence(experiments, Child(path, "experiments"));
  // Parse everything first so that a config error leaves no file behind.
  std::vector<std::pair<std::string, CampaignRun>> runs;
  for (size_t i = 0; i < experiments.size(); ++i) {
    const std::string key = Child(Child(path, "experiments"), i);
    CampaignRun run = ReadRun(reader, experiments[i], key, base, static_cast<int>(i));
    runs.emplace_back(reader.String(experiments[i]["file"], Child(key, "file")), run);
  }
  if (check_only) return true;
  if (!CreateSimulationFolder(out_dir, error)) return false;
  for (const auto& [file, run] : runs) {
    Trajectory trajectory;
    if (!SimulateRun(model, truth, run, &trajectory, error)) {
      *error = file + ": " + *error;
      return false;
    }
    if (degrees) {  // heading, rudder angles and yaw rate in degrees (deg/s), as logs have them
      for (size_t c = 0; c < trajectory.names.size(); ++c) {
        const std::string& name = trajectory.names[c];
        if (name == "psi" || name == "psi_true" || name == "delta" || name == "delta_true" ||
            name == "r_true") {
          for (double& value : trajectory.columns[c]) value /= kDegree;
        }
      }
    }
    *error = OutputFileNameProblem(file, "simulation.experiments[].file");
    if (!error->empty()) return false;
    if (!WriteTrajectoryCsv((fs::path(out_dir) / file).string(), trajectory, error)) return false;
  }
  return true;
}

}  // namespace

ModelFamily MmgFamily() {
  return {"mmg",
          "MMG standard 3-DOF manoeuvring model (Yasukawa & Yoshimura 2015): hull polynomial in "
          "v', r', rudder with flow straightening and wake, propeller thrust from K_T(J)",
          MakeModel, Simulate};
}

}  // namespace vesselid::mmg

#include "problems/eriksen2dof/eriksen_config.h"

#include <cmath>
#include <filesystem>

#include "engine/base/file_name.h"
#include "engine/config/family_simulation.h"
#include "problems/eriksen2dof/campaign.h"
#include "problems/eriksen2dof/handles.h"

namespace vesselid::eriksen2dof {
namespace {

namespace fs = std::filesystem;

//   model: {family: eriksen2dof, speed_scale: 10, yaw_rate_scale: 0.5}
std::unique_ptr<ModelHandle> MakeModel(const YamlReader& reader, const YAML::Node& node,
                                       const std::string& path) {
  reader.CheckMap(node, path, {"family", "speed_scale", "yaw_rate_scale"});
  Model model;
  reader.Read(node, path, "speed_scale", &model.speed_scale);
  reader.Read(node, path, "yaw_rate_scale", &model.yaw_rate_scale);
  if (!(model.speed_scale > 0.0)) reader.Fail(node["speed_scale"], Child(path, "speed_scale"), "must be > 0");
  if (!(model.yaw_rate_scale > 0.0)) {
    reader.Fail(node["yaw_rate_scale"], Child(path, "yaw_rate_scale"), "must be > 0");
  }
  return MakeHandle(model);
}

// Reads `[lower, upper]` into two doubles.
void ReadRange(const YamlReader& reader, const YAML::Node& map, const std::string& path,
               const std::string& name, double* lower, double* upper) {
  if (!map[name]) return;
  const std::vector<double> range = reader.Doubles(map[name], Child(path, name));
  if (range.size() != 2) reader.Fail(map[name], Child(path, name), "expected [lower, upper]");
  *lower = range[0];
  *upper = range[1];
}

//   simulation: {steps_file, validation_file, seed, sample_period,
//                rudder_settings, throttle_settings, throttle_step, rudder_step,
//                hold: {min_settle, max_settle, min_steady, max_steady},
//                validation: {runs, duration, throttle: [lo, hi]},
//                environment: {current_speed, current_direction_deg, wind_speed,
//                              wind_direction_deg, gust_sd, gust_time_constant},
//                noise: {position, course_deg, sog, rot_deg}}
bool Simulate(const YamlReader& reader, const YAML::Node& simulation, const ModelHandle&,
              const std::string& out_dir, bool check_only, std::string* error) {
  const std::string path = "simulation";
  if (!simulation) reader.Fail(simulation, path, "missing: the config has no simulation section");
  reader.CheckMap(simulation, path,
                  {"steps_file", "validation_file", "seed", "sample_period", "rudder_settings",
                   "throttle_settings", "throttle_step", "rudder_step", "hold", "validation",
                   "environment", "noise"});
  std::string steps_file = "steps.csv", validation_file = "validation.csv";
  reader.Read(simulation, path, "steps_file", &steps_file);
  reader.Read(simulation, path, "validation_file", &validation_file);
  CampaignOptions o;
  int seed = static_cast<int>(o.seed);
  reader.Read(simulation, path, "seed", &seed);
  o.seed = static_cast<unsigned>(seed);
  reader.Read(simulation, path, "sample_period", &o.sample_period);
  if (simulation["rudder_settings"]) {
    o.rudder_settings = reader.Doubles(simulation["rudder_settings"], Child(path, "rudder_settings"));
  }
  if (simulation["throttle_settings"]) {
    o.throttle_settings =
        reader.Doubles(simulation["throttle_settings"], Child(path, "throttle_settings"));
  }
  reader.Read(simulation, path, "throttle_step", &o.throttle_step);
  reader.Read(simulation, path, "rudder_step", &o.rudder_step);
  if (const YAML::Node hold = simulation["hold"]) {
    const std::string key = Child(path, "hold");
    reader.CheckMap(hold, key, {"min_settle", "max_settle", "min_steady", "max_steady"});
    reader.Read(hold, key, "min_settle", &o.min_settle);
    reader.Read(hold, key, "max_settle", &o.max_settle);
    reader.Read(hold, key, "min_steady", &o.min_steady);
    reader.Read(hold, key, "max_steady", &o.max_steady);
  }
  if (const YAML::Node validation = simulation["validation"]) {
    const std::string key = Child(path, "validation");
    reader.CheckMap(validation, key, {"runs", "duration", "throttle"});
    reader.Read(validation, key, "runs", &o.validation_runs);
    reader.Read(validation, key, "duration", &o.validation_duration);
    ReadRange(reader, validation, key, "throttle", &o.validation_throttle_min,
              &o.validation_throttle_max);
  }
  if (const YAML::Node environment = simulation["environment"]) {
    const std::string key = Child(path, "environment");
    reader.CheckMap(environment, key,
                    {"current_speed", "current_direction_deg", "wind_speed",
                     "wind_direction_deg", "gust_sd", "gust_time_constant"});
    reader.Read(environment, key, "current_speed", &o.current_speed);
    reader.Read(environment, key, "wind_speed", &o.wind_speed);
    reader.Read(environment, key, "gust_sd", &o.gust_sd);
    reader.Read(environment, key, "gust_time_constant", &o.gust_time_constant);
    ReadDegrees(reader, environment, key, "current_direction_deg", &o.current_direction);
    ReadDegrees(reader, environment, key, "wind_direction_deg", &o.wind_direction);
  }
  if (const YAML::Node noise = simulation["noise"]) {
    const std::string key = Child(path, "noise");
    reader.CheckMap(noise, key, {"position", "course_deg", "sog", "rot_deg"});
    reader.Read(noise, key, "position", &o.position_noise);
    reader.Read(noise, key, "sog", &o.sog_noise);
    ReadDegrees(reader, noise, key, "course_deg", &o.course_noise);
    ReadDegrees(reader, noise, key, "rot_deg", &o.rot_noise);
  }
  std::string invalid;
  if (!o.IsValid(&invalid)) reader.Fail(simulation, path, invalid);
  // At most: every level of every step run held for its longest settling and steady phases,
  // each run's warm-up, and the validation runs.
  const double levels = (2.0 / o.throttle_step + 1.0) * o.rudder_settings.size() +
                        (2.0 / o.rudder_step + 1.0) * o.throttle_settings.size();
  const double runs = o.rudder_settings.size() + o.throttle_settings.size();
  const double seconds = levels * (o.max_settle + o.max_steady) + runs * (o.warm_up + o.run_gap) +
                         o.validation_runs * (o.validation_duration + o.warm_up);
  reader.CheckLimit(simulation, path, seconds / o.step, reader.limits().integration_steps,
                    "limits.integration_steps; the campaign's longest duration over its step");
  for (const auto& [name, key] : {std::pair{steps_file, "simulation.steps_file"},
                                  std::pair{validation_file, "simulation.validation_file"}}) {
    *error = OutputFileNameProblem(name, key);
    if (!error->empty()) return false;
  }
  if (check_only) return true;
  if (!CreateSimulationFolder(out_dir, error)) return false;
  const CraftParameters craft;
  Trajectory steps, validation;
  return SimulateStepCampaign(craft, o, &steps, error) &&
         SimulateValidationRuns(craft, o, &validation, error) &&
         WriteTrajectoryCsv((fs::path(out_dir) / steps_file).string(), steps, error) &&
         WriteTrajectoryCsv((fs::path(out_dir) / validation_file).string(), validation, error);
}

}  // namespace

ModelFamily EriksenFamily() {
  return {"eriksen2dof",
          "Eriksen-Breivik 2-DOF speed/yaw-rate model of a high-speed craft (seed 004)", MakeModel,
          Simulate};
}

}  // namespace vesselid::eriksen2dof

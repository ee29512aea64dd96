#include "problems/erunsal6dof/erunsal_config.h"

#include <filesystem>

#include "engine/base/file_name.h"
#include "engine/config/family_simulation.h"
#include "problems/erunsal6dof/campaign.h"
#include "problems/erunsal6dof/handles.h"

namespace vesselid::erunsal6dof {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = M_PI / 180.0;

Model ReadModel(const YamlReader& reader, const YAML::Node& node, const std::string& path) {
  reader.CheckMap(node, path, {"family", "constants", "active_dofs"});
  Model model;
  if (const YAML::Node constants = node["constants"]) {
    const std::string key = Child(path, "constants");
    reader.CheckMap(constants, key, {"m", "l_y", "A_x", "A_y", "k_z", "k_phi", "k_theta", "rho_air"});
    Constants& c = model.constants;
    reader.Read(constants, key, "m", &c.m);
    reader.Read(constants, key, "l_y", &c.l_y);
    reader.Read(constants, key, "A_x", &c.A_x);
    reader.Read(constants, key, "A_y", &c.A_y);
    reader.Read(constants, key, "k_z", &c.k_z);
    reader.Read(constants, key, "k_phi", &c.k_phi);
    reader.Read(constants, key, "k_theta", &c.k_theta);
    reader.Read(constants, key, "rho_air", &c.rho_air);
    if (!(c.m > 0)) reader.Fail(constants, Child(key, "m"), "mass must be > 0");
  }
  if (const YAML::Node dofs = node["active_dofs"]) {
    const std::string key = Child(path, "active_dofs");
    model.active.fill(false);
    const std::vector<std::string> names = reader.Strings(dofs, key);
    for (size_t i = 0; i < names.size(); ++i) {
      int dof;
      if (!StringToDof(names[i], &dof)) {
        reader.Fail(dofs[i], Child(key, i),
                    "unknown DOF '" + names[i] + "' (surge, sway, heave, roll, pitch, yaw)");
      }
      model.active[dof] = true;
    }
  }
  return model;
}

std::unique_ptr<ModelHandle> MakeModel(const YamlReader& reader, const YAML::Node& node,
                                       const std::string& path) {
  return MakeHandle(ReadModel(reader, node, path));
}

CampaignRun ReadRun(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                    const ModelInfo& info) {
  reader.CheckMap(node, key,
                  {"file", "type", "duration", "initial_state", "mean_command", "differential",
                   "step_time", "zigzag_heading_deg", "seed", "active_dofs"});
  CampaignRun run;
  if (!node["file"]) reader.Fail(node, key, "missing key 'file'");
  if (!node["type"]) reader.Fail(node, key, "missing key 'type'");
  run.file = reader.String(node["file"], Child(key, "file"));
  const std::string type = reader.String(node["type"], Child(key, "type"));
  if (!StringToCampaignType(type, &run.type)) {
    reader.Fail(node["type"], Child(key, "type"),
                "unknown run type '" + type + "' (thrust, decay, spiral, zigzag, random)");
  }
  reader.Read(node, key, "duration", &run.duration);
  if (!(run.duration > 0)) reader.Fail(node, Child(key, "duration"), "must be > 0");
  if (const YAML::Node initial = node["initial_state"]) {
    const std::string path = Child(key, "initial_state");
    std::map<std::string, double> values = reader.DoubleMap(initial, path);
    for (const auto& [name, value] : values) {
      int index = info.StateIndex(name);
      if (index < 0) {
        reader.Fail(initial, Child(path, name), "unknown state (" + JoinNames(info.states) + ")");
      }
      run.initial_state[index] = value;
    }
  }
  reader.Read(node, key, "mean_command", &run.mean_command);
  reader.Read(node, key, "differential", &run.differential);
  reader.Read(node, key, "step_time", &run.step_time);
  double heading = run.zigzag_heading / kDegree;
  reader.Read(node, key, "zigzag_heading_deg", &heading);
  run.zigzag_heading = heading * kDegree;
  int seed = static_cast<int>(run.seed);
  reader.Read(node, key, "seed", &seed);
  run.seed = static_cast<unsigned>(seed);
  if (const YAML::Node dofs = node["active_dofs"]) {
    YAML::Node model(YAML::NodeType::Map);
    model["active_dofs"] = dofs;
    run.active = ReadModel(reader, model, key).active;
  }
  if (!(run.step_time > 0)) reader.Fail(node, Child(key, "step_time"), "must be > 0");
  return run;
}

bool Simulate(const YamlReader& reader, const YAML::Node& simulation, const ModelHandle& model,
              const std::string& out_dir, bool check_only, std::string* error) {
  const std::string path = "simulation";
  if (!simulation) reader.Fail(simulation, path, "missing: the config has no simulation section");
  reader.CheckMap(simulation, path,
                  {"model", "truth", "sample_time", "substeps", "noise", "experiments"});
  // The campaign runs with every DOF active; `simulation.model` may set the vessel's
  // constants (default: the reference tugboat).
  YAML::Node full(YAML::NodeType::Map);
  if (simulation["model"]) full = YAML::Clone(simulation["model"]);
  Model free_model = ReadModel(reader, full, Child(path, "model"));
  free_model.active.fill(true);
  const ModelInfo info = free_model.Info();

  const std::vector<double> truth =
      ReadTruth(reader, simulation["truth"], Child(path, "truth"), info, ReferenceParameters());
  CampaignOptions options;
  reader.Read(simulation, path, "sample_time", &options.sample_time);
  reader.Read(simulation, path, "substeps", &options.substeps);
  if (!(options.sample_time > 0) || options.substeps < 1) {
    reader.Fail(simulation, path, "sample_time must be > 0 and substeps >= 1");
  }
  if (const YAML::Node noise = simulation["noise"]) {
    const std::string key = Child(path, "noise");
    reader.CheckMap(noise, key, {"position", "angle_deg", "force"});
    reader.Read(noise, key, "position", &options.noise.position);
    double angle = options.noise.angle / kDegree;
    reader.Read(noise, key, "angle_deg", &angle);
    options.noise.angle = angle * kDegree;
    reader.Read(noise, key, "force", &options.noise.force);
  }
  const YAML::Node experiments = simulation["experiments"];
  if (!experiments) reader.Fail(simulation, Child(path, "experiments"), "missing");
  reader.CheckSequence(experiments, Child(path, "experiments"));
  std::vector<CampaignRun> runs;
  for (size_t i = 0; i < experiments.size(); ++i) {
    const std::string key = Child(Child(path, "experiments"), i);
    runs.push_back(ReadRun(reader, experiments[i], key, info));
    reader.CheckLimit(experiments[i]["duration"], Child(key, "duration"),
                      runs.back().duration / options.sample_time * options.substeps,
                      reader.limits().integration_steps, "limits.integration_steps");
  }
  if (check_only) return true;
  if (!CreateSimulationFolder(out_dir, error)) return false;
  for (const CampaignRun& run : runs) {
    Model truth_model = free_model;
    truth_model.active = run.active;
    if (run.type == CampaignRun::Type::kThrust) truth_model.active.fill(false);
    const std::unique_ptr<ModelHandle> run_handle = MakeHandle(truth_model);
    const ModelHandle& handle = *run_handle;
    Trajectory trajectory;
    if (!SimulateCampaignRun(handle, truth, options, run, &trajectory, error)) {
      *error = run.file + ": " + *error;
      return false;
    }
    *error = OutputFileNameProblem(run.file, "simulation.experiments[].file");
    if (!error->empty()) return false;
    const std::string target = (fs::path(out_dir) / run.file).string();
    if (!WriteTrajectoryCsv(target, trajectory, error)) return false;
  }
  return true;
}

}  // namespace

ModelFamily ErunsalFamily() {
  return {"erunsal6dof", "Erunsal 6-DOF vessel (Fossen form) with DOF restriction", MakeModel,
          Simulate};
}

}  // namespace vesselid::erunsal6dof

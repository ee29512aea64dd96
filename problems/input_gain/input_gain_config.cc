#include "problems/input_gain/input_gain_config.h"

#include <filesystem>
#include <utility>

#include "engine/base/file_name.h"
#include "engine/config/family_simulation.h"
#include "problems/input_gain/campaign.h"
#include "problems/input_gain/field_log.h"
#include "problems/input_gain/handles.h"

namespace vesselid::input_gain {
namespace {

namespace fs = std::filesystem;

//   thrust: [n, "n|n|"], dead_zone: true   (thrust_law.h; default: both terms, dead zone)
ThrustLaw ReadThrustLaw(const YamlReader& reader, const YAML::Node& model,
                        const std::string& path) {
  ThrustLaw law;
  if (const YAML::Node list = model["thrust"]) {
    const std::string key = Child(path, "thrust");
    const std::vector<std::string> names = reader.Strings(list, key);
    if (names.empty()) reader.Fail(list, key, "lists no term (n, n|n|)");
    law.linear = law.quadratic = false;
    for (size_t j = 0; j < names.size(); ++j) {
      ThrustLaw before = law;
      if (!StringToThrustTerm(names[j], &law)) {
        reader.Fail(list[j], Child(key, j), "unknown thrust term '" + names[j] + "' (n, n|n|)");
      }
      if (before.linear == law.linear && before.quadratic == law.quadratic) {
        reader.Fail(list[j], Child(key, j), "term listed twice");
      }
    }
  }
  reader.Read(model, path, "dead_zone", &law.dead_zone);
  return law;
}

//   model: {family: input_gain, type: static | dynamic,
//           bases: {u: [1, u, "|u|u", vr, rr], v: [...], r: [...]},
//           thrust: [n, "n|n|"], dead_zone: true}
std::unique_ptr<ModelHandle> MakeModel(const YamlReader& reader, const YAML::Node& model,
                                       const std::string& path) {
  reader.CheckMap(model, path, {"family", "type", "bases", "thrust", "dead_zone"});
  Bases bases;
  if (const YAML::Node node = model["bases"]) {
    const std::string key = Child(path, "bases");
    reader.CheckMap(node, key, {"u", "v", "r"});
    const char* equations[3] = {"u", "v", "r"};
    for (int i = 0; i < 3; ++i) {
      const YAML::Node list = node[equations[i]];
      if (!list) continue;
      const std::string where = Child(key, equations[i]);
      std::vector<std::string> names = reader.Strings(list, where);
      bases.terms[i].clear();
      for (size_t j = 0; j < names.size(); ++j) {
        int term;
        if (!StringToTerm(names[j], &term)) {
          std::string known;
          for (const std::string& n : TermNames()) known += (known.empty() ? "" : ", ") + n;
          reader.Fail(list[j], Child(where, j), "unknown term '" + names[j] + "' (" + known + ")");
        }
        for (int existing : bases.terms[i]) {
          if (existing == term) reader.Fail(list[j], Child(where, j), "term listed twice");
        }
        bases.terms[i].push_back(term);
      }
    }
  }
  const std::string type =
      model["type"] ? reader.String(model["type"], Child(path, "type")) : "static";
  const ThrustLaw law = ReadThrustLaw(reader, model, path);
  if (type == "static") return MakeStaticHandle(bases, law);
  if (type == "dynamic") return MakeDynamicHandle(bases, law);
  reader.Fail(model["type"], Child(path, "type"),
              "unknown input-gain variant '" + type + "' (static, dynamic)");
}

//   field_log: {origin: [lat, lon], rate: 10, jitter_ms: 30, zero_fix_segment, stale_segment,
//               stale_fixes: 4, short_segment, short_s: 2}   (field_log.h)
bool ReadFieldLog(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                  int segments, FieldLogOptions* options) {
  if (!node) return false;
  reader.CheckMap(node, key,
                  {"origin", "rate", "jitter_ms", "zero_fix_segment", "stale_segment",
                   "stale_fixes", "short_segment", "short_s"});
  if (const YAML::Node origin = node["origin"]) {
    const std::vector<double> values = reader.Doubles(origin, Child(key, "origin"));
    if (values.size() != 2) reader.Fail(origin, Child(key, "origin"), "expected [lat, lon]");
    options->origin_lat = values[0];
    options->origin_lon = values[1];
  }
  reader.Read(node, key, "rate", &options->rate);
  double jitter_ms = options->jitter * 1e3;
  reader.Read(node, key, "jitter_ms", &jitter_ms);
  options->jitter = jitter_ms * 1e-3;
  for (const auto& [name, index] :
       {std::pair<const char*, int*>{"zero_fix_segment", &options->zero_fix_segment},
        {"stale_segment", &options->stale_segment},
        {"short_segment", &options->short_segment}}) {
    reader.Read(node, key, name, index);
    if (*index >= segments) {
      reader.Fail(node[name], Child(key, name),
                  "segment " + std::to_string(*index) + " of " + std::to_string(segments) +
                      " (indices from 0)");
    }
  }
  reader.Read(node, key, "stale_fixes", &options->stale_fixes);
  reader.Read(node, key, "short_s", &options->short_s);
  std::string invalid;
  if (!options->IsValid(&invalid)) reader.Fail(node, key, invalid);
  return true;
}

//   simulation: {file, segments, duration_min, seed, noise: {position, heading_deg},
//                vessel: catamaran | quadratic_usv, segment_s: [min, max],
//                defects: {abrupt_start_segment, glitch_segment}, field_log: {...},
//                forward_only: false, planned: {file, lead_in_s: 30}}
bool Simulate(const YamlReader& reader, const YAML::Node& simulation, const ModelHandle&,
              const std::string& out_dir, bool check_only, std::string* error) {
  const std::string path = "simulation";
  if (!simulation) reader.Fail(simulation, path, "missing: the config has no simulation section");
  reader.CheckMap(simulation, path,
                  {"file", "segments", "duration_min", "seed", "noise", "vessel", "segment_s",
                   "defects", "field_log", "forward_only", "planned"});
  if (!simulation["file"]) reader.Fail(simulation, Child(path, "file"), "missing");
  const std::string file = reader.String(simulation["file"], Child(path, "file"));
  CampaignOptions options;
  reader.Read(simulation, path, "segments", &options.segments);
  double minutes = options.total_duration / 60.0;
  reader.Read(simulation, path, "duration_min", &minutes);
  options.total_duration = minutes * 60.0;
  int seed = static_cast<int>(options.seed);
  reader.Read(simulation, path, "seed", &seed);
  options.seed = static_cast<unsigned>(seed);
  if (const YAML::Node noise = simulation["noise"]) {
    const std::string key = Child(path, "noise");
    reader.CheckMap(noise, key, {"position", "heading_deg"});
    reader.Read(noise, key, "position", &options.gnss_noise);
    double heading = options.heading_noise * 180.0 / M_PI;
    reader.Read(noise, key, "heading_deg", &heading);
    options.heading_noise = heading * M_PI / 180.0;
  }
  if (const YAML::Node range = simulation["segment_s"]) {
    const std::vector<double> bounds = reader.Doubles(range, Child(path, "segment_s"));
    if (bounds.size() != 2) reader.Fail(range, Child(path, "segment_s"), "expected [min, max]");
    options.min_segment = bounds[0];
    options.max_segment = bounds[1];
  }
  if (const YAML::Node defects = simulation["defects"]) {
    const std::string key = Child(path, "defects");
    reader.CheckMap(defects, key, {"abrupt_start_segment", "glitch_segment", "glitch_offset"});
    reader.Read(defects, key, "abrupt_start_segment", &options.defects.abrupt_start_segment);
    reader.Read(defects, key, "glitch_segment", &options.defects.glitch_segment);
    reader.Read(defects, key, "glitch_offset", &options.defects.glitch_offset);
  }
  reader.Read(simulation, path, "forward_only", &options.forward_only);
  if (const YAML::Node planned = simulation["planned"]) {
    // A plan of `vesselid design` (t, u_L, u_R), relative to the config's folder.
    const std::string key = Child(path, "planned");
    reader.CheckMap(planned, key, {"file", "lead_in_s"});
    if (!planned["file"]) reader.Fail(planned, key, "missing key 'file'");
    std::string plan = reader.String(planned["file"], Child(key, "file"));
    if (fs::path(plan).is_relative())
      plan = (fs::path(reader.file()).parent_path() / plan).string();
    reader.Read(planned, key, "lead_in_s", &options.lead_in);
    Trajectory table;
    std::string message;
    if (!ReadTrajectoryCsv(plan, &table, &message))
      reader.Fail(planned["file"], Child(key, "file"), message);
    const int left = table.Find("u_L"), right = table.Find("u_R");
    if (left < 0 || right < 0)
      reader.Fail(planned["file"], Child(key, "file"), plan + ": needs columns u_L and u_R");
    options.planned_t = table.t;
    options.planned_left = table.columns[left];
    options.planned_right = table.columns[right];
  }
  std::string vessel = "catamaran";
  if (simulation["vessel"]) vessel = reader.String(simulation["vessel"], Child(path, "vessel"));
  if (vessel != "catamaran" && vessel != "quadratic_usv") {
    reader.Fail(simulation["vessel"], Child(path, "vessel"),
                "unknown vessel '" + vessel + "' (catamaran, quadratic_usv)");
  }
  // A field log samples the campaign every step and writes what a logger would (field_log.h).
  FieldLogOptions log;
  const bool field_log = ReadFieldLog(reader, simulation["field_log"], Child(path, "field_log"),
                                      options.segments, &log);
  if (field_log) {
    options.step = kFieldLogCampaignStep;
    options.gnss_period = options.ahrs_period = options.step;
    options.gnss_offset = 0.0;
    options.truth_columns = false;
  }
  std::string invalid;
  if (!options.IsValid(&invalid)) reader.Fail(simulation, path, invalid);
  const double simulated_time = options.planned_t.empty()
                                    ? options.total_duration
                                    : options.lead_in + options.planned_t.back();
  reader.CheckLimit(simulation["duration_min"], Child(path, "duration_min"),
                    simulated_time / options.step, reader.limits().integration_steps,
                    "limits.integration_steps");
  if (check_only) return true;
  if (!CreateSimulationFolder(out_dir, error)) return false;
  Trajectory campaign;
  const bool simulated =
      vessel == "catamaran" ? SimulateCampaign(CatamaranParameters(), options, &campaign, error)
                            : SimulateCampaign(QuadraticUsvParameters(), options, &campaign, error);
  if (!simulated) return false;
  if (field_log && !MakeFieldLog(campaign, log, options.seed, &campaign, error)) return false;
  *error = OutputFileNameProblem(file, "simulation.file");
  if (!error->empty()) return false;
  return WriteTrajectoryCsv((fs::path(out_dir) / file).string(), campaign, error);
}

}  // namespace

ModelFamily InputGainFamily() {
  return {"input_gain",
          "joint input-gain model of a twin-propeller catamaran (static or dynamic propellers)",
          MakeModel, Simulate};
}

}  // namespace vesselid::input_gain

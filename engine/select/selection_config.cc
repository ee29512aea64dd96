#include "engine/select/selection_config.h"

#include <filesystem>
#include <set>

#include "engine/config/config.h"
#include "engine/config/yaml_reader.h"

namespace vesselid {
namespace {

// The top-level keys a candidate may replace.
const std::vector<std::string>& ReplaceableKeys() {
  static const std::vector<std::string> keys = {
      "model", "experiment_defaults", "experiments", "sets", "stages", "fusion",
      "final", "final_validation"};
  return keys;
}

// The candidate's config text: the file's root with the candidate's keys replaced, and
// without `select` and `study`.
std::string CandidateText(const YAML::Node& root, const YAML::Node& candidate) {
  YAML::Node config(YAML::NodeType::Map);
  for (const auto& item : root) {
    const std::string key = item.first.as<std::string>();
    if (key == "select" || key == "study" || candidate[key]) continue;
    config[key] = item.second;
  }
  for (const std::string& key : ReplaceableKeys()) {
    if (candidate[key]) config[key] = candidate[key];
  }
  YAML::Emitter out;
  out << config;
  return out.c_str();
}

}  // namespace

bool LoadSelection(const std::string& path, const std::string& data_dir,
                   const ModelRegistry& registry, SelectionSetup* setup, std::string* error) {
  ConfigSource source;
  source.path = path;
  source.data_dir = data_dir;
  return LoadSelection(source, registry, setup, error);
}

bool LoadSelection(const ConfigSource& source, const ModelRegistry& registry,
                   SelectionSetup* setup, std::string* error) {
  const std::string& path = source.path;
  const std::string& data_dir = source.data_dir;
  const YamlReader reader = source.text.empty() ? YamlReader(path) : YamlReader(path, source.text);
  SelectionSetup out;
  std::vector<std::pair<std::string, std::string>> texts;  // name, config text
  YAML::Node select;
  try {
    const YAML::Node root = reader.Load();
    // Checked before it is held: a node of a missing key cannot be assigned.
    if (!root["select"]) reader.Fail(root, "select", "missing: the config has no select section");
    select.reset(root["select"]);
    reader.CheckMap(select, "select", {"experiments", "folds", "outputs", "threads", "candidates"});
    if (const YAML::Node folds = select["folds"]) {
      if (folds.IsScalar() && folds.Scalar() == "leave_one_run_out") {
        out.options.folds = 0;
      } else {
        out.options.folds = reader.Int(folds, "select.folds");
        if (out.options.folds < 2) {
          reader.Fail(folds, "select.folds", "leave_one_run_out, or a number of folds >= 2");
        }
      }
    }
    if (select["outputs"])
      out.options.outputs = reader.Strings(select["outputs"], "select.outputs");
    reader.Read(select, "select", "threads", &out.options.cases.threads);
    if (out.options.cases.threads < 0) {
      reader.Fail(select["threads"], "select.threads", "must be >= 0 (0: every core)");
    }
    const YAML::Node candidates = select["candidates"];
    if (!candidates) reader.Fail(select, "select.candidates", "missing");
    reader.CheckSequence(candidates, "select.candidates");
    if (candidates.size() < 2) {
      reader.Fail(candidates, "select.candidates", "needs at least two candidates");
    }
    std::set<std::string> names;
    for (size_t i = 0; i < candidates.size(); ++i) {
      const std::string key = Child("select.candidates", i);
      std::vector<std::string> allowed = ReplaceableKeys();
      allowed.push_back("name");
      reader.CheckMap(candidates[i], key, allowed);
      if (!candidates[i]["name"]) reader.Fail(candidates[i], key, "missing key 'name'");
      const std::string name = reader.Name(candidates[i]["name"], Child(key, "name"));
      if (!names.insert(name).second) {
        reader.Fail(candidates[i]["name"], Child(key, "name"), "'" + name + "' given twice");
      }
      texts.emplace_back(name, CandidateText(root, candidates[i]));
    }
  } catch (const ConfigError& e) {
    *error = e.what();
    return false;
  }
  // Each candidate as a config of its own; files resolve as the file's own would.
  const std::string data =
      !data_dir.empty() ? data_dir : std::filesystem::path(path).parent_path().string();
  for (const auto& [name, text] : texts) {
    ConfigSource candidate;
    candidate.path = path + " (candidate '" + name + "')";
    candidate.text = text;
    candidate.data_dir = data.empty() ? "." : data;
    candidate.in_memory = source.in_memory;
    ConfigFile file;
    if (!LoadConfig(candidate, registry, &file, error)) return false;
    file.run.path = path;  // the file the run's outputs and checkpoint name
    out.candidates.push_back({name, std::move(file.run)});
  }
  // The runs: a set or a list (sets expanded), else the first stage's experiments.
  const RunConfig& first = out.candidates.front().config;
  try {
    if (const YAML::Node runs = select["experiments"]) {
      const std::vector<std::string> listed =
          runs.IsScalar() ? std::vector<std::string>{reader.String(runs, "select.experiments")}
                          : reader.Strings(runs, "select.experiments");
      for (const std::string& name : listed) {
        const auto set = first.experiment_sets.find(name);
        if (set != first.experiment_sets.end()) {
          out.options.runs.insert(out.options.runs.end(), set->second.begin(), set->second.end());
        } else if (first.FindExperiment(name) != nullptr) {
          out.options.runs.push_back(name);
        } else {
          reader.Fail(runs, "select.experiments",
                      "'" + name + "' is neither an experiment nor a set of the config");
        }
      }
    } else if (!first.stages.empty()) {
      out.options.runs = first.stages.front().experiments;
    }
  } catch (const ConfigError& e) {
    *error = e.what();
    return false;
  }
  *setup = std::move(out);
  return true;
}

}  // namespace vesselid

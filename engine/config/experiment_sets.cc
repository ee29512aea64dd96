#include "engine/config/experiment_sets.h"

#include <map>

namespace vesselid {

namespace {

std::string SetNames(const RunConfig& config) {
  std::string names;
  for (const auto& set : config.experiment_sets) names += (names.empty() ? "" : ", ") + set.first;
  return names;
}

// Where an experiment of a list came from, for the message on one listed twice.
std::string Origin(const std::string& set) {
  return set.empty() ? "by name" : "in set '" + set + "'";
}

}  // namespace

void ReadExperimentSets(const YamlReader& reader, const YAML::Node& node, RunConfig* config) {
  if (!node.IsMap()) reader.Fail(node, "sets", "expected a map of named lists of experiments");
  for (const auto& item : node) {
    const std::string name = reader.KeyName(item.first, "sets");
    const std::string key = Child("sets", name);
    if (config->FindExperiment(name) != nullptr) {
      reader.Fail(item.first, key, "a set cannot have the name of an experiment");
    }
    std::vector<std::string> names = ExperimentNames(reader, item.second, key, *config);
    if (names.empty()) reader.Fail(item.second, key, "a set holds at least one experiment");
    config->experiment_sets[name] = std::move(names);
  }
}

std::vector<std::string> ExperimentNames(const YamlReader& reader, const YAML::Node& node,
                                         const std::string& key, const RunConfig& config) {
  const auto& sets = config.experiment_sets;
  if (node.IsScalar()) {
    const auto set = sets.find(node.Scalar());
    if (set != sets.end()) return set->second;
    reader.Fail(node, key,
                sets.empty() ? "expected a list of experiment names, e.g. [a, b] (the config "
                               "has no sets)"
                             : "no set named '" + node.Scalar() + "' (sets: " + SetNames(config) +
                                   "; a list of experiments is [a, b])");
  }
  const std::vector<std::string> items = reader.Strings(node, key);
  std::vector<std::string> names;
  std::map<std::string, std::string> listed;  // experiment -> the set it came from ("": by name)
  for (size_t i = 0; i < items.size(); ++i) {
    std::vector<std::string> expanded;
    std::string from;
    if (config.FindExperiment(items[i]) != nullptr) {
      expanded = {items[i]};
    } else if (const auto set = sets.find(items[i]); set != sets.end()) {
      expanded = set->second;
      from = items[i];
    } else {
      reader.Fail(node[i], Child(key, i),
                  std::string("no experiment ") + (sets.empty() ? "" : "or set ") + "named '" +
                      items[i] + "'");
    }
    for (const std::string& name : expanded) {
      const auto [seen, fresh] = listed.emplace(name, from);
      if (!fresh) {
        reader.Fail(node[i], Child(key, i),
                    "experiment '" + name + "' is listed twice (" + Origin(seen->second) + " and " +
                        Origin(from) + ")");
      }
      names.push_back(name);
    }
  }
  return names;
}

}  // namespace vesselid

// docs/config_reference.md names every key the config readers accept, and no key they refuse.
// The readers are asked, not read: every map of every shipped config is handed to them with
// one key they cannot know, and each names the keys it allows ("unknown key (allowed: ...)");
// every allowed key missing from the map is then given a map (or a list of one map) holding
// such a key, which names the keys below it, and so on down the whole tree. Maps keyed by
// the model's names (parameters, inputs, outputs, states) are left out: their keys are the
// model's, listed by `vesselid findings`'s models in docs/models.md.
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/config/config.h"
#include "engine/design/design_config.h"
#include "gtest/gtest.h"
#include "problems/registry.h"
#include "yaml-cpp/yaml.h"

namespace vesselid {
namespace config_reference_test {

constexpr char kProbe[] = "zz_probe";

// A place in a YAML tree: map keys and sequence indices.
struct Step {
  std::string key;
  int index = -1;
};
using Path = std::vector<Step>;

// The node at `path` (reset, not assignment: assigning a YAML::Node writes into the tree).
YAML::Node At(YAML::Node node, const Path& path) {
  for (const Step& s : path) {
    const YAML::Node next = s.index >= 0 ? node[s.index] : node[s.key];
    node.reset(next);
  }
  return node;
}

// The path with indices left out ("stages.global"): where in the schema a key sits.
std::string SchemaPath(const Path& path) {
  std::string text;
  for (const Step& s : path) {
    if (s.index < 0 && s.key != "<<") text += (text.empty() ? "" : ".") + s.key;
  }
  return text.empty() ? "(top level)" : text;
}

std::string Emit(const YAML::Node& root) {
  YAML::Emitter out;
  out << root;
  return out.c_str();
}

// The keys of one model family's configs. Maps keyed by the model's names are not walked
// and the model's names are left out of the lists (input_range: {<input>: ..., skip}).
class KeyTree {
 public:
  // The config the next Explore walks, and the experiments whose records are not needed.
  // `scalars` (shared by the families' trees): the keys found to hold neither a map nor a
  // list of maps, by schema path, which the trees do not probe again.
  void SetConfig(std::string name, std::set<std::string> in_memory,
                 std::set<std::string>* scalars) {
    name_ = std::move(name);
    in_memory_ = std::move(in_memory);
    scalars_ = scalars;
  }

  // The keys allowed anywhere below `path` of `root`, by schema path.
  void Explore(const YAML::Node& root, const Path& path) {
    const YAML::Node node = At(root, path);
    if (node.IsSequence()) {
      for (size_t i = 0; i < node.size(); ++i) {
        Path child = path;
        child.push_back({"", static_cast<int>(i)});
        Explore(root, child);
      }
      return;
    }
    if (!node.IsMap()) return;
    const std::string schema = SchemaPath(path);
    std::vector<std::string> present;
    for (const auto& item : node) present.push_back(item.first.as<std::string>());
    if (!visited_.insert(schema + "|" + Join(present)).second) return;

    YAML::Node probed = YAML::Clone(root);
    At(probed, path)[kProbe] = 1;
    const std::vector<std::string> allowed = Allowed(probed);
    Record(schema, allowed);
    for (const std::string& key : present) {
      Path child = path;
      child.push_back({key});
      Explore(root, child);
    }
    if (allowed.empty()) return;
    // A map keyed by the model's names: what one name's value holds (input_noise.delta).
    const std::vector<std::string> keys =
        IsNameMap(allowed) ? std::vector<std::string>{allowed.front()} : allowed;
    for (const std::string& key : keys) {
      const std::string where = schema + "." + key;
      if (node[key] || tried_.count(where) || scalars_->count(where)) continue;
      tried_.insert(where);
      // A map below the key, or a list of maps: the list only where the reader asked for
      // one (a scalar's key refuses both, and the list's probe would double the test's time).
      for (int list = 0; list < 2; ++list) {
        if (list && last_error_.find("expected a list") == std::string::npos) break;
        YAML::Node grown = YAML::Clone(root);
        YAML::Node inner(YAML::NodeType::Map);
        inner[kProbe] = 1;
        if (list) {
          YAML::Node sequence(YAML::NodeType::Sequence);
          sequence.push_back(inner);
          At(grown, path)[key] = sequence;
        } else {
          At(grown, path)[key] = inner;
        }
        Path child = path;
        child.push_back({key});
        if (list) child.push_back({"", 0});
        const std::vector<std::string> below = Allowed(grown);
        if (below.empty()) {
          // The reader wants a scalar, or a list of them: so in every family's tree.
          if (IsScalarRefusal(last_error_)) scalars_->insert(where);
          continue;
        }
        // The probe key named keys of the new map: explore it with a valid map in place.
        YAML::Node valid = YAML::Clone(grown);
        At(valid, child).remove(kProbe);
        Record(SchemaPath(child), below);
        Explore(valid, child);
        break;
      }
    }
  }

  const std::map<std::string, std::set<std::string>>& allowed() const { return allowed_; }
  const std::set<std::string>& model_names() const { return model_names_; }
  void AddModelNames(const ModelInfo& info) {
    for (const auto* list : {&info.parameters, &info.inputs, &info.outputs, &info.states}) {
      model_names_.insert(list->begin(), list->end());
    }
  }

 private:
  static std::string Join(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += x + ",";
    return s;
  }

  void Record(const std::string& schema, const std::vector<std::string>& keys) {
    for (const std::string& key : keys) {
      if (!model_names_.count(key)) allowed_[schema].insert(key);
    }
  }

  // A probe map refused where a number, string, flag or integer (or a list of them) goes.
  static bool IsScalarRefusal(const std::string& error) {
    static const std::regex scalar(R"(: expected (a number|a string|true or false|an integer))");
    return std::regex_search(error, scalar);
  }

  bool IsNameMap(const std::vector<std::string>& keys) const {
    if (keys.empty()) return true;
    for (const std::string& k : keys) {
      if (!model_names_.count(k)) return false;
    }
    return true;
  }

  // The keys the reader names when it meets the probe key in `root`, or none.
  std::vector<std::string> Allowed(const YAML::Node& root) const {
    ConfigSource source;
    source.path = name_;
    source.text = Emit(root);
    source.in_memory = in_memory_;
    static const ModelRegistry registry = DefaultRegistry();  // once, not per probe
    ConfigFile config;
    std::string error;
    if (LoadConfig(source, registry, &config, &error)) {
      SimulateConfig(config, "", &error, /*check_only=*/true);
    }
    if (root["design"] && error.find(kProbe) == std::string::npos) {  // `vesselid design`'s
      DesignOptions options;
      LoadDesign(name_, &options, &error, source.text);
    }
    last_error_ = error;
    static const std::regex unknown(std::string(kProbe) + R"(: unknown key \(allowed: ([^)]*)\))");
    std::smatch match;
    if (!std::regex_search(error, match, unknown)) return {};
    std::vector<std::string> keys;
    std::stringstream list(match[1].str());
    std::string key;
    while (std::getline(list, key, ',')) {
      const size_t first = key.find_first_not_of(' ');
      keys.push_back(key.substr(first));
    }
    return keys;
  }

  mutable std::string last_error_;  // the reader's message for the last probe
  std::string name_;
  std::set<std::string> in_memory_;
  std::set<std::string> model_names_;
  std::set<std::string> visited_, tried_;
  std::set<std::string>* scalars_ = nullptr;
  std::map<std::string, std::set<std::string>> allowed_;
};

// Every `word:` in the indented blocks of docs/config_reference.md, comments included.
std::set<std::string> DocumentedKeys() {
  std::ifstream in(std::string(VESSELID_SOURCE_DIR) + "/docs/config_reference.md");
  std::set<std::string> keys;
  const std::regex key(R"((^|[^A-Za-z0-9_.-])([A-Za-z_][A-Za-z0-9_]*):)");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("    ", 0) != 0) continue;
    for (std::sregex_iterator it(line.begin(), line.end(), key), end; it != end; ++it) {
      keys.insert((*it)[2]);
    }
  }
  return keys;
}

const char* const kShippedConfigs[] = {
    "nomoto_cargo.yaml",        "nomoto_cargo_noise.yaml", "nomoto_patrol.yaml",
    "nomoto_patrol_noise.yaml", "nomoto_tanker.yaml",      "input_gain_static.yaml",
    "input_gain_dynamic.yaml",  "input_gain_usv_log.yaml", "erunsal_hierarchy.yaml",
    "eriksen_2dof.yaml",        "mmg_kvlcc2.yaml",         "design_cargo.yaml",
    "design_input_gain.yaml"};

struct ReaderKeys {
  std::map<std::string, std::set<std::string>> by_schema;  // allowed keys by schema path
  std::set<std::string> all;                               // the union
  std::set<std::string> model_names;                       // of every shipped config's model
};

// The allowed keys of every shipped config's tree; a family's configs share one tree (a map
// met in one is not probed again in the next). Computed once (about 6 s).
const ReaderKeys& ShippedReaderKeys() {
  static const ReaderKeys keys = [] {
  const ModelRegistry registry = DefaultRegistry();
  std::map<std::string, KeyTree> families;
  std::set<std::string> scalars;
  for (const char* file : kShippedConfigs) {
    const std::string path = std::string(VESSELID_SOURCE_DIR) + "/configs/" + file;
    ConfigFile config;
    std::string error;
    EXPECT_TRUE(LoadConfigFile(path, "", registry, &config, &error)) << error;
    if (config.run.model == nullptr) continue;
    std::set<std::string> experiments;
    for (const auto& e : config.run.experiments) experiments.insert(e.name);
    KeyTree& tree = families[config.run.family];
    tree.SetConfig(path, experiments, &scalars);
    tree.AddModelNames(config.run.model->info());
    tree.Explore(YAML::LoadFile(path), {});
  }
  ReaderKeys result;
  for (const auto& [family, tree] : families) {
    for (const auto& [schema, keys] : tree.allowed()) {
      result.by_schema[schema].insert(keys.begin(), keys.end());
      result.all.insert(keys.begin(), keys.end());
    }
    result.model_names.insert(tree.model_names().begin(), tree.model_names().end());
  }
  return result;
  }();
  return keys;
}

// Words followed by a colon in the blocks that are not keys: set names of the examples and
// prose of the comments ("default: all", "| given: ...").
const std::set<std::string> kNotKeys = {"held_out", "training", "default", "true", "false",
                                        "given", "last", "selected"};

// Both ways in one test: the probe takes about 6 s.
TEST(ConfigReference, NamesEveryKeyTheReadersAcceptAndNoOther) {
  const std::set<std::string> documented = DocumentedKeys();
  ASSERT_GT(documented.size(), 100u) << "docs/config_reference.md's blocks were not found";
  const ReaderKeys& reader = ShippedReaderKeys();
  ASSERT_GT(reader.by_schema.size(), 40u) << "the probe reached too few maps";
  std::string missing;
  for (const auto& [schema, keys] : reader.by_schema) {
    for (const std::string& key : keys) {
      if (!documented.count(key)) missing += "\n  " + schema + "." + key;
    }
  }
  EXPECT_TRUE(missing.empty()) << "keys the readers accept that docs/config_reference.md does "
                                  "not name:" << missing;
  std::string refused;
  for (const std::string& key : documented) {
    if (!reader.all.count(key) && !reader.model_names.count(key) && !kNotKeys.count(key)) {
      refused += " " + key;
    }
  }
  EXPECT_TRUE(refused.empty()) << "docs/config_reference.md names keys no reader accepts:"
                               << refused;

}

}  // namespace config_reference_test
}  // namespace vesselid

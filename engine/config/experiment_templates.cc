#include "engine/config/experiment_templates.h"

#include <glob.h>

#include <algorithm>
#include <filesystem>

#include "engine/config/data_folder.h"

namespace vesselid {

namespace {

namespace fs = std::filesystem;

std::string KeyText(const YAML::Node& key) { return key.IsScalar() ? key.Scalar() : ""; }

// New maps made inside one yaml-cpp memory that the document's joins. Inserting a document
// node into a map of its own fresh memory copies the set of every node the document holds
// into that memory (yaml-cpp's memory merge), so a fresh map per experiment costs the
// document's size each and a config of n experiments n^2 (10 000 experiments: over 20 GB).
// Here the first insertion moves the document into the arena's memory once; later ones find
// it there.
class NodeArena {
 public:
  YAML::Node NewMap() {
    maps_.push_back(YAML::Node(YAML::NodeType::Map));
    return static_cast<const YAML::Node&>(maps_)[maps_.size() - 1];
  }

 private:
  YAML::Node maps_{YAML::NodeType::Sequence};
};

// A new scalar, placed at `written` for messages.
YAML::Node Scalar(YamlReader* reader, const std::string& text, const YAML::Node& written) {
  YAML::Node node(text);
  reader->Place(node, written);
  return node;
}

// `own` over `defaults`: a new map placed at `own`. Maps on both sides merge recursively,
// anything else of `own` replaces the default, and an own null drops it. `top`: the
// experiment's map itself, whose own `file` or `files` replaces a default `file`.
YAML::Node WithDefaults(YamlReader* reader, NodeArena* arena, const YAML::Node& own,
                        const YAML::Node& defaults, bool top) {
  YAML::Node merged = arena->NewMap();
  reader->Place(merged, own);
  for (const auto& item : own) {
    if (item.second.IsNull()) continue;
    const YAML::Node base = defaults[KeyText(item.first)];
    if (item.second.IsMap() && base.IsDefined() && base.IsMap()) {
      merged.force_insert(item.first, WithDefaults(reader, arena, item.second, base, false));
    } else {
      merged.force_insert(item.first, item.second);
    }
  }
  const bool own_file = top && (own["file"].IsDefined() || own["files"].IsDefined());
  for (const auto& item : defaults) {
    const std::string name = KeyText(item.first);
    if (own[name].IsDefined() || (own_file && name == "file")) continue;
    merged.force_insert(item.first, item.second);
  }
  return merged;
}

// The files matching `pattern` (relative to `folder` unless absolute), sorted, each as the
// path relative to `folder`.
std::vector<std::string> MatchingFiles(const YamlReader& reader, const YAML::Node& node,
                                       const std::string& key, const std::string& pattern,
                                       const std::string& folder) {
  const bool absolute = fs::path(pattern).is_absolute();
  const std::string full =
      absolute || folder.empty() ? pattern : (fs::path(folder) / pattern).string();
  glob_t found;
  const int status = ::glob(full.c_str(), 0, nullptr, &found);
  std::vector<std::string> files;
  if (status == 0) {
    for (size_t i = 0; i < found.gl_pathc; ++i) {
      const fs::path match = found.gl_pathv[i];
      files.push_back(absolute || folder.empty() ? match.string()
                                                 : match.lexically_relative(folder).string());
    }
  }
  const size_t matched = status == 0 ? found.gl_pathc : 0;
  globfree(&found);
  if (matched > reader.limits().files) {
    reader.Fail(node, key,
                "'" + pattern + "' matches " + std::to_string(matched) + " files, more than the " +
                    std::to_string(reader.limits().files) + " a run may read (limits.files)");
  }
  const std::string where =
      absolute ? "" : " in " + (folder.empty() ? std::string("the current folder") : folder);
  if (status == GLOB_NOMATCH || (status == 0 && files.empty())) {
    reader.Fail(node, key, "no file matches '" + pattern + "'" + where);
  }
  if (status != 0)
    reader.Fail(node, key, "cannot list the files matching '" + pattern + "'" + where);
  std::sort(files.begin(), files.end());
  return files;
}

// One experiment per file matching the entry's `files`, named by its `name` pattern.
void ExpandFiles(YamlReader* reader, NodeArena* arena, const YAML::Node& node,
                 const std::string& path, const std::string& data_folder,
                 std::vector<ExperimentEntry>* entries) {
  const YAML::Node files = node["files"];
  const std::string key = Child(path, "files");
  if (node["file"].IsDefined()) {
    reader->Fail(files, key,
                 "file and files cannot be combined (files makes one experiment "
                 "per file it matches)");
  }
  const std::string pattern = reader->String(files, key);
  std::string name = "{stem}";
  const YAML::Node name_node = node["name"];
  if (name_node.IsDefined()) {
    name = reader->String(name_node, Child(path, "name"));
    if (name.find("{stem}") == std::string::npos) {
      reader->Fail(name_node, Child(path, "name"),
                   "with files, the name holds {stem} (each file's name without its extension), "
                   "e.g. \"zz_{stem}\"");
    }
  }
  const YAML::Node& name_at = name_node.IsDefined() ? name_node : files;
  const std::vector<std::string> matches = MatchingFiles(*reader, files, key, pattern, data_folder);
  for (const std::string& file : matches) {
    const std::string outside = OutsideDataFolder(file, data_folder, reader->limits());
    if (!outside.empty()) reader->Fail(files, key, "'" + pattern + "' matches " + outside);
  }
  for (const std::string& file : matches) {
    std::string experiment = name;
    const std::string stem = fs::path(file).stem().string();
    for (size_t at = experiment.find("{stem}"); at != std::string::npos;
         at = experiment.find("{stem}", at + stem.size())) {
      experiment.replace(at, 6, stem);
    }
    YAML::Node entry = arena->NewMap();
    reader->Place(entry, node);
    entry.force_insert(Scalar(reader, "name", name_at), Scalar(reader, experiment, name_at));
    entry.force_insert(Scalar(reader, "file", files), Scalar(reader, file, files));
    for (const auto& item : node) {
      const std::string item_key = KeyText(item.first);
      if (item_key != "name" && item_key != "files") entry.force_insert(item.first, item.second);
    }
    entries->push_back({entry, path + "(" + experiment + ")"});
  }
}

}  // namespace

const std::vector<std::string>& ExperimentKeys() {
  static const std::vector<std::string> keys{
      "name",           "file",     "files",         "inputs",  "outputs",
      "interpolation",  "weights",  "initial_state", "degrees", "window",
      "segment_length", "segments", "input_range",   "wrap",    "separator",
      "time",           "position", "screen",        "resample", "input_noise", "bad_cells"};
  return keys;
}

std::vector<ExperimentEntry> ExpandExperiments(YamlReader* reader, const YAML::Node& root,
                                               const std::string& data_folder) {
  const YAML::Node experiments = root["experiments"];
  if (!experiments.IsDefined()) reader->Fail(root, "experiments", "missing key");
  reader->CheckSequence(experiments, "experiments");
  const YAML::Node defaults = root["experiment_defaults"];
  if (defaults.IsDefined()) {
    const std::string key = "experiment_defaults";
    std::vector<std::string> allowed;
    for (const std::string& k : ExperimentKeys()) {
      if (k != "name" && k != "files") allowed.push_back(k);
    }
    if (defaults.IsMap()) {
      for (const char* own : {"name", "files"}) {
        if (defaults[own].IsDefined()) {
          reader->Fail(defaults[own], Child(key, own),
                       "every experiment gives its own (a name, or a files pattern)");
        }
      }
    }
    reader->CheckMap(defaults, key, allowed);
  }
  std::vector<ExperimentEntry> entries;
  NodeArena arena;
  size_t matched = 0;  // files of the `files` patterns so far
  for (size_t i = 0; i < experiments.size(); ++i) {
    const std::string path = Child("experiments", i);
    if (!experiments[i].IsMap()) reader->Fail(experiments[i], path, "expected a map");
    const YAML::Node node = defaults.IsDefined()
                                ? WithDefaults(reader, &arena, experiments[i], defaults, true)
                                : experiments[i];
    if (node["files"].IsDefined()) {
      const size_t before = entries.size();
      ExpandFiles(reader, &arena, node, path, data_folder, &entries);
      matched += entries.size() - before;
      if (matched > reader->limits().files) {
        reader->Fail(node["files"], Child(path, "files"),
                     "the files patterns match " + std::to_string(matched) +
                         " files together, more than the " +
                         std::to_string(reader->limits().files) + " a run may read (limits.files)");
      }
    } else {
      entries.push_back({node, path});
    }
  }
  return entries;
}

}  // namespace vesselid

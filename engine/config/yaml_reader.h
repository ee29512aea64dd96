// Reading YAML configs with messages that name the file, line and key path. Every map is
// checked against the keys it may hold, so a misspelt key is an error, not a silent default.
// Errors are thrown as ConfigError inside the config layer only; its public entry points
// return them as messages.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/base/work_limits.h"
#include "yaml-cpp/yaml.h"

namespace vesselid {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class YamlReader {
 public:
  explicit YamlReader(std::string file) : file_(std::move(file)) {}
  // A config given as text (YAML, or JSON, which is YAML too); `name` stands for the file
  // in messages.
  YamlReader(std::string name, std::string text)
      : file_(std::move(name)), text_(std::move(text)), from_text_(true) {}

  // Loads the file (or the text); throws ConfigError on a missing file, one that is not a regular
  // file or larger than kMaxConfigBytes, a syntax error or a map with a key given twice. A UTF-8
  // byte-order mark is skipped. Merge keys (`<<: *defaults`) are resolved (yaml_merge.h).
  YAML::Node Load() const;

  // Messages about `built`, a node the config templates made (experiment_templates.h), name
  // the line of `written`, what it was made from.
  void Place(const YAML::Node& built, const YAML::Node& written);

  const std::string& file() const { return file_; }

  // The config's `limits` section (work_limits.h), read before anything it bounds.
  const WorkLimits& limits() const { return limits_; }
  void set_limits(const WorkLimits& limits) { limits_ = limits; }
  // Fails unless count <= limit, naming the count, the limit and its key.
  void CheckLimit(const YAML::Node& node, const std::string& key, double count, std::uint64_t limit,
                  const std::string& limit_key) const;

  // "file:line: key" of a node, for messages about it written after the config is read.
  std::string Where(const YAML::Node& node, const std::string& key) const;

  // "file:line: key: what"; "file:line: what" for the top level (key "").
  [[noreturn]] void Fail(const YAML::Node& node, const std::string& key,
                         const std::string& what) const;

  // The name of a map's key `name` (in the map at `key`): a list or map as a key is an error.
  std::string KeyName(const YAML::Node& name, const std::string& key) const;

  // Requires a map whose keys are all in `allowed`.
  void CheckMap(const YAML::Node& node, const std::string& key,
                const std::vector<std::string>& allowed) const;
  void CheckSequence(const YAML::Node& node, const std::string& key) const;

  double Double(const YAML::Node& node, const std::string& key) const;
  int Int(const YAML::Node& node, const std::string& key) const;
  bool Bool(const YAML::Node& node, const std::string& key) const;
  std::string String(const YAML::Node& node, const std::string& key) const;
  // A string that names output files (an experiment's or a stage's name): refused when it is
  // empty, holds a control character or is too long (base/file_name.h).
  std::string Name(const YAML::Node& node, const std::string& key) const;
  std::vector<std::string> Strings(const YAML::Node& node, const std::string& key) const;
  std::vector<double> Doubles(const YAML::Node& node, const std::string& key) const;
  std::map<std::string, std::string> StringMap(const YAML::Node& node,
                                               const std::string& key) const;
  std::map<std::string, double> DoubleMap(const YAML::Node& node, const std::string& key) const;

  // Optional members: `out` keeps its value when the key is absent.
  void Read(const YAML::Node& map, const std::string& path, const std::string& name,
            double* out) const;
  void Read(const YAML::Node& map, const std::string& path, const std::string& name,
            int* out) const;
  void Read(const YAML::Node& map, const std::string& path, const std::string& name,
            bool* out) const;
  void Read(const YAML::Node& map, const std::string& path, const std::string& name,
            std::string* out) const;

 private:
  std::string file_;
  std::string text_;
  bool from_text_ = false;
  WorkLimits limits_;
  std::vector<std::pair<YAML::Node, YAML::Mark>> placed_;  // built node -> where written
};

// "a.b" or "a[2]" paths for messages.
inline std::string Child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}
inline std::string Child(const std::string& path, size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

}  // namespace vesselid

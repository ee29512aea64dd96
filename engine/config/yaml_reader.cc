#include "engine/config/yaml_reader.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <string_view>

#include "engine/base/file_name.h"
#include "engine/base/input_file.h"
#include "engine/base/number_text.h"
#include "engine/config/yaml_merge.h"
#include "yaml-cpp/depthguard.h"

namespace vesselid {

namespace {

// Every map of `node` and below, each visited once (an alias shares its anchor's node, so
// a file of nested aliases is not walked exponentially often).
void CheckUniqueKeys(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                     std::set<std::pair<int, int>>* visited) {
  if (!node.IsMap() && !node.IsSequence()) return;
  if (!visited->insert({node.Mark().line, node.Mark().column}).second) return;
  if (node.IsSequence()) {
    for (size_t i = 0; i < node.size(); ++i) {
      CheckUniqueKeys(reader, node[i], Child(key, i), visited);
    }
    return;
  }
  std::map<std::string, int> lines;  // key -> line (1-based)
  for (const auto& item : node) {
    const std::string name = item.first.IsScalar() ? item.first.Scalar() : "";
    if (!name.empty()) {
      const auto [seen, fresh] = lines.emplace(name, item.first.Mark().line + 1);
      if (!fresh) {
        reader.Fail(item.first, Child(key, name),
                    "given twice (lines " + std::to_string(seen->second) + " and " +
                        std::to_string(item.first.Mark().line + 1) +
                        "); a YAML map holds each key once" +
                        (name == "<<" ? " (merge several maps with <<: [*a, *b])" : ""));
      }
    }
    CheckUniqueKeys(reader, item.second, Child(key, name), visited);
  }
}

// Deepest flow nesting ([ and {) a config may have: yaml-cpp tokenises a whole document before
// it finds one too deep, and 5 000 000 nested [ (10 MB) take it 1.35 GB.
constexpr int kMaxFlowDepth = 64;

// The 1-based line where `text`'s flow collections nest deeper than kMaxFlowDepth (brackets in
// quotes and comments aside); 0 when they do not.
int FlowTooDeep(const std::string& text) {
  int depth = 0, line = 1;
  char quote = 0;
  bool comment = false;
  char previous = '\n';
  for (char c : text) {
    if (c == '\n') {
      ++line;
      comment = false;
    } else if (comment) {
    } else if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '#' && (previous == ' ' || previous == '\t' || previous == '\n')) {
      comment = true;
    } else if ((c == '"' || c == '\'') &&
               std::string_view(" \t\n[{,:-").find(previous) != std::string_view::npos) {
      quote = c;  // a quoted scalar starts here (an apostrophe inside a word does not)
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxFlowDepth) return line;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
    previous = c;
  }
  return 0;
}

}  // namespace

YAML::Node YamlReader::Load() const {
  std::string error;
  if (from_text_ && text_.size() > kMaxConfigBytes) {
    throw ConfigError(file_ + ": a config of " + std::to_string(text_.size()) + " bytes; at most " +
                      std::to_string(kMaxConfigBytes) + " are read");
  }
  if (!from_text_ && !CheckInputFile(file_, "config file", kMaxConfigBytes, "", &error)) {
    throw ConfigError(error);
  }
  std::string text = text_;
  if (!from_text_) {
    std::ifstream in(file_, std::ios::binary);
    if (!in) throw ConfigError(file_ + ": cannot open file");
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (const int line = FlowTooDeep(text); line > 0) {
    throw ConfigError(file_ + ":" + std::to_string(line) + ": YAML lists or maps nested deeper than " +
                      std::to_string(kMaxFlowDepth) + " levels");
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp's own message for this is "bad file".
    throw ConfigError(file_ + ":" + std::to_string(e.mark.line + 1) +
                      ": YAML syntax error: lists or maps nested too deeply");
  } catch (const YAML::Exception& e) {
    throw ConfigError(file_ + ":" + std::to_string(e.mark.line + 1) +
                      ": YAML syntax error: " + e.msg);
  }
  std::set<std::pair<int, int>> visited;
  CheckUniqueKeys(*this, root, "", &visited);
  ResolveMergeKeys(*this, root);
  return root;
}

void YamlReader::Place(const YAML::Node& built, const YAML::Node& written) {
  placed_.emplace_back(built, written.Mark());
}

void YamlReader::CheckLimit(const YAML::Node& node, const std::string& key, double count,
                            std::uint64_t limit, const std::string& limit_key) const {
  if (count <= static_cast<double>(limit)) return;
  char text[200];
  std::snprintf(text, sizeof(text), "%.6g is more than the limit of %.6g (%s)", count,
                static_cast<double>(limit), limit_key.c_str());
  Fail(node, key, text);
}

std::string YamlReader::Where(const YAML::Node& node, const std::string& key) const {
  try {
    Fail(node, key, "");
  } catch (const ConfigError& e) {
    const std::string text = e.what();
    return text.substr(0, text.size() - 2);  // without the ": " of the empty message
  }
}

void YamlReader::Fail(const YAML::Node& node, const std::string& key,
                      const std::string& what) const {
  std::string where = file_;
  YAML::Mark mark = node.IsDefined() ? node.Mark() : YAML::Mark::null_mark();
  for (size_t i = 0; mark.is_null() && node.IsDefined() && i < placed_.size(); ++i) {
    if (placed_[i].first.is(node)) mark = placed_[i].second;
  }
  if (mark.line >= 0) where += ":" + std::to_string(mark.line + 1);
  // An empty key is the top level of the file.
  throw ConfigError(where + ": " + (key.empty() ? "" : key + ": ") + what);
}

std::string YamlReader::KeyName(const YAML::Node& name, const std::string& key) const {
  // as<std::string>() would throw "bad conversion", naming neither the key nor the map.
  if (!name.IsScalar() && !name.IsNull()) {
    Fail(name, key, "a key must be a name, not a list or map");
  }
  return name.as<std::string>();
}

void YamlReader::CheckMap(const YAML::Node& node, const std::string& key,
                          const std::vector<std::string>& allowed) const {
  if (!node.IsMap()) Fail(node, key, "expected a map");
  for (const auto& item : node) {
    const std::string name = KeyName(item.first, key);
    bool known = false;
    for (const std::string& a : allowed) known = known || a == name;
    if (!known) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      Fail(item.first, Child(key, name), "unknown key (allowed: " + list + ")");
    }
  }
}

void YamlReader::CheckSequence(const YAML::Node& node, const std::string& key) const {
  if (!node.IsSequence()) Fail(node, key, "expected a list");
}

double YamlReader::Double(const YAML::Node& node, const std::string& key) const {
  if (!node.IsScalar()) Fail(node, key, "expected a number");
  const std::string text = node.Scalar();
  if (text == "inf" || text == "+inf" || text == ".inf") return INFINITY;
  if (text == "-inf" || text == "-.inf") return -INFINITY;
  double value;
  if (ParseFiniteNumber(text, &value)) return value;
  Fail(node, key, "'" + text + "' is not a finite number");
}

int YamlReader::Int(const YAML::Node& node, const std::string& key) const {
  if (!node.IsScalar()) Fail(node, key, "expected an integer");
  try {
    size_t used = 0;
    long value = std::stol(node.Scalar(), &used);
    if (used == node.Scalar().size() && value >= INT32_MIN && value <= INT32_MAX) {
      return static_cast<int>(value);
    }
  } catch (const std::exception&) {
  }
  Fail(node, key, "'" + node.Scalar() + "' is not an integer");
}

bool YamlReader::Bool(const YAML::Node& node, const std::string& key) const {
  if (node.IsScalar()) {
    const std::string& text = node.Scalar();
    if (text == "true" || text == "yes" || text == "on") return true;
    if (text == "false" || text == "no" || text == "off") return false;
  }
  Fail(node, key, "expected true or false");
}

std::string YamlReader::String(const YAML::Node& node, const std::string& key) const {
  if (!node.IsScalar()) Fail(node, key, "expected a string");
  return node.Scalar();
}

std::string YamlReader::Name(const YAML::Node& node, const std::string& key) const {
  const std::string name = String(node, key);
  const std::string problem = NameProblem(name);
  if (!problem.empty()) Fail(node, key, "the name " + problem);
  return name;
}

std::vector<std::string> YamlReader::Strings(const YAML::Node& node, const std::string& key) const {
  CheckSequence(node, key);
  std::vector<std::string> values;
  for (size_t i = 0; i < node.size(); ++i) values.push_back(String(node[i], Child(key, i)));
  return values;
}

std::vector<double> YamlReader::Doubles(const YAML::Node& node, const std::string& key) const {
  CheckSequence(node, key);
  std::vector<double> values;
  for (size_t i = 0; i < node.size(); ++i) values.push_back(Double(node[i], Child(key, i)));
  return values;
}

std::map<std::string, std::string> YamlReader::StringMap(const YAML::Node& node,
                                                         const std::string& key) const {
  if (!node.IsMap()) Fail(node, key, "expected a map");
  std::map<std::string, std::string> values;
  for (const auto& item : node) {
    const std::string name = KeyName(item.first, key);
    values[name] = String(item.second, Child(key, name));
  }
  return values;
}

std::map<std::string, double> YamlReader::DoubleMap(const YAML::Node& node,
                                                    const std::string& key) const {
  if (!node.IsMap()) Fail(node, key, "expected a map");
  std::map<std::string, double> values;
  for (const auto& item : node) {
    const std::string name = KeyName(item.first, key);
    values[name] = Double(item.second, Child(key, name));
  }
  return values;
}

void YamlReader::Read(const YAML::Node& map, const std::string& path, const std::string& name,
                      double* out) const {
  if (map[name]) *out = Double(map[name], Child(path, name));
}
void YamlReader::Read(const YAML::Node& map, const std::string& path, const std::string& name,
                      int* out) const {
  if (map[name]) *out = Int(map[name], Child(path, name));
}
void YamlReader::Read(const YAML::Node& map, const std::string& path, const std::string& name,
                      bool* out) const {
  if (map[name]) *out = Bool(map[name], Child(path, name));
}
void YamlReader::Read(const YAML::Node& map, const std::string& path, const std::string& name,
                      std::string* out) const {
  if (map[name]) *out = String(map[name], Child(path, name));
}

}  // namespace vesselid

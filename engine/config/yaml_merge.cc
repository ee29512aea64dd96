#include "engine/config/yaml_merge.h"

#include <set>
#include <utility>
#include <vector>

namespace vesselid {

namespace {

// A node as the parser placed it: an alias shares its anchor's node and so its position.
using Position = std::pair<int, int>;
Position At(const YAML::Node& node) { return {node.Mark().line, node.Mark().column}; }

// The merge key is the plain scalar "<<" (tag "?"); a quoted one is an ordinary key.
bool IsMergeKey(const YAML::Node& key) {
  return key.IsScalar() && key.Tag() == "?" && key.Scalar() == "<<";
}

std::string KindOf(const YAML::Node& node) {
  if (node.IsSequence()) return "a list";
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  return "nothing";
}

class MergeResolver {
 public:
  explicit MergeResolver(const YamlReader& reader) : reader_(reader) {}

  // Resolves every map below `node` first, so a merged map arrives with its own merges done;
  // each node once (a file of nested aliases is not walked exponentially often).
  void Resolve(const YAML::Node& node, const std::string& key) {
    if (!node.IsMap() && !node.IsSequence()) return;
    const Position at = At(node);
    if (done_.count(at) != 0 || !open_.insert(at).second) return;
    if (node.IsSequence()) {
      for (size_t i = 0; i < node.size(); ++i) Resolve(node[i], Child(key, i));
    } else {
      std::vector<std::pair<YAML::Node, YAML::Node>> merge;  // the `<<` item (keys are unique)
      for (const auto& item : node) {
        const std::string name = item.first.IsScalar() ? item.first.Scalar() : "";
        if (IsMergeKey(item.first)) merge.emplace_back(item.first, item.second);
        Resolve(item.second, Child(key, name));
      }
      if (!merge.empty()) Merge(node, merge[0].first, merge[0].second, Child(key, "<<"));
    }
    open_.erase(at);
    done_.insert(at);
  }

 private:
  // Rewrites `map` in place (it keeps its line and every alias of it sees the result): its
  // own keys, with the merged maps' other keys where the `<<` line was.
  void Merge(YAML::Node map, const YAML::Node& merge_key, const YAML::Node& value,
             const std::string& key) {
    std::vector<YAML::Node> sources;
    if (value.IsMap()) {
      sources.push_back(value);
    } else if (value.IsSequence() && value.size() > 0) {
      for (size_t i = 0; i < value.size(); ++i) {
        if (!value[i].IsMap()) {
          reader_.Fail(
              value[i], Child(key, i),
              "a merge key's list holds maps (e.g. <<: [*a, *b]), not " + KindOf(value[i]));
        }
        sources.push_back(value[i]);
      }
    } else {
      reader_.Fail(value, key,
                   "a merge key takes a map or a list of maps (e.g. <<: *defaults or "
                   "<<: [*a, *b]), not " +
                       (value.IsSequence() ? std::string("an empty list") : KindOf(value)));
    }
    for (const YAML::Node& source : sources) {
      if (open_.count(At(source)) != 0) {
        reader_.Fail(merge_key, key, "merges a map that contains this one");
      }
    }
    std::set<std::string> present;
    for (const auto& item : map) {
      if (!IsMergeKey(item.first)) present.insert(item.first.IsScalar() ? item.first.Scalar() : "");
    }
    std::vector<std::pair<YAML::Node, YAML::Node>> before, after;
    for (const auto& item : map) {
      before.emplace_back(item.first, item.second);
      if (!IsMergeKey(item.first)) {
        after.emplace_back(item.first, item.second);
        continue;
      }
      // Earlier maps win: a key is taken from the first map that has it.
      for (const YAML::Node& source : sources) {
        for (const auto& merged : source) {
          const std::string name = merged.first.IsScalar() ? merged.first.Scalar() : "";
          if (present.insert(name).second) after.emplace_back(merged.first, merged.second);
        }
      }
    }
    for (const auto& item : before) map.remove(item.first);
    for (const auto& item : after) map.force_insert(item.first, item.second);
  }

  const YamlReader& reader_;
  std::set<Position> open_;  // maps and lists being resolved (the path from the root)
  std::set<Position> done_;
};

}  // namespace

void ResolveMergeKeys(const YamlReader& reader, const YAML::Node& root) {
  MergeResolver(reader).Resolve(root, "");
}

}  // namespace vesselid

// The `bootstrap` key of a regression stage (group_bootstrap.h):
//
//   bootstrap: 200                     # replicates (0: none)
//   bootstrap: {runs: 200, lambda: held | selected, seed: 1,
//               blocks: 20}            # blocks: least-squares stages only
//
// The replicates use every core; their results do not depend on how many (no key).
#include "engine/config/config_sections.h"

namespace vesselid {

void ReadBootstrap(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                   bool blocks, GroupBootstrapOptions* bootstrap) {
  if (node.IsScalar()) {
    bootstrap->runs = reader.Int(node, path);
  } else {
    std::vector<std::string> keys = {"runs", "lambda", "seed"};
    if (blocks) keys.push_back("blocks");
    reader.CheckMap(node, path, keys);
    reader.Read(node, path, "runs", &bootstrap->runs);
    if (const YAML::Node lambda = node["lambda"]) {
      const std::string value = reader.String(lambda, Child(path, "lambda"));
      if (value != "held" && value != "selected") {
        reader.Fail(lambda, Child(path, "lambda"), "expected held or selected");
      }
      bootstrap->hold_lambda = value == "held";
    }
    if (const YAML::Node seed = node["seed"]) {
      const int value = reader.Int(seed, Child(path, "seed"));
      if (value < 0) reader.Fail(seed, Child(path, "seed"), "must be >= 0");
      bootstrap->seed = static_cast<unsigned>(value);
    }
    reader.Read(node, path, "blocks", &bootstrap->blocks);
  }
  std::string error;
  if (!bootstrap->IsValid(&error)) reader.Fail(node, path, error);
}

}  // namespace vesselid

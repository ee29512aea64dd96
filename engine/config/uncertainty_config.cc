// A stage's `uncertainty` key: true | false, or
//   {method: auto | hessian | sandwich_hac, bandwidth: auto | <blocks>,
//    aggregation: auto | <time nodes>, kernel: bartlett | quadratic_spectral,
//    prewhiten: true | false}
#include "engine/config/config_sections.h"

namespace vesselid {

void ReadUncertainty(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                     StageOptions* options) {
  if (node.IsScalar()) {
    options->compute_uncertainty = reader.Bool(node, path);
    return;
  }
  reader.CheckMap(node, path, {"method", "bandwidth", "aggregation", "kernel", "prewhiten"});
  options->compute_uncertainty = true;
  UncertaintyOptions& u = options->uncertainty;
  if (const YAML::Node n = node["method"]) {
    const std::string text = reader.String(n, Child(path, "method"));
    if (!StringToUncertaintyMethod(text, &u.method)) {
      reader.Fail(n, Child(path, "method"),
                  "unknown method '" + text + "' (auto, hessian, sandwich_hac)");
    }
  }
  if (const YAML::Node n = node["kernel"]) {
    const std::string text = reader.String(n, Child(path, "kernel"));
    if (!StringToHacKernel(text, &u.hac.kernel)) {
      reader.Fail(n, Child(path, "kernel"),
                  "unknown kernel '" + text + "' (bartlett, quadratic_spectral)");
    }
  }
  if (const YAML::Node n = node["bandwidth"]) {
    const std::string key = Child(path, "bandwidth");
    if (n.IsScalar() && n.Scalar() == "auto") {
      u.hac.bandwidth = 0.0;
    } else {
      u.hac.bandwidth = reader.Double(n, key);
      if (!(u.hac.bandwidth >= 1.0)) reader.Fail(n, key, "must be auto or >= 1 (blocks)");
    }
  }
  if (const YAML::Node n = node["aggregation"]) {
    const std::string key = Child(path, "aggregation");
    if (n.IsScalar() && n.Scalar() == "auto") {
      u.hac.aggregation = 0;
    } else {
      u.hac.aggregation = reader.Int(n, key);
      if (u.hac.aggregation < 1) reader.Fail(n, key, "must be auto or >= 1 (time nodes)");
    }
  }
  reader.Read(node, path, "prewhiten", &u.hac.prewhiten);
}

}  // namespace vesselid

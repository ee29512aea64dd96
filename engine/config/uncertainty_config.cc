// A stage's `uncertainty` key: true | false, or
//   {method: auto | hessian | sandwich_hac | block_bootstrap | experiment_bootstrap,
//    bandwidth: auto | <blocks>, aggregation: auto | <time nodes>,
//    kernel: bartlett | quadratic_spectral, prewhiten: true | false,
//    runs: <replicates >= 10>, block_length: auto | <seconds>, seed: <integer>,
//    input_noise: auto | off, input_noise_runs: <refits >= 5>}
#include "engine/config/config_sections.h"
#include "engine/run/bootstrap_uncertainty.h"
#include "engine/run/input_noise_uncertainty.h"

namespace vesselid {

void ReadUncertainty(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                     StageOptions* options) {
  if (node.IsScalar()) {
    options->compute_uncertainty = reader.Bool(node, path);
    return;
  }
  reader.CheckMap(node, path, {"method", "bandwidth", "aggregation", "kernel", "prewhiten", "runs",
                               "block_length", "seed", "input_noise", "input_noise_runs"});
  options->compute_uncertainty = true;
  UncertaintyOptions& u = options->uncertainty;
  if (const YAML::Node n = node["method"]) {
    const std::string text = reader.String(n, Child(path, "method"));
    if (!StringToUncertaintyMethod(text, &u.method)) {
      reader.Fail(n, Child(path, "method"),
                  "unknown method '" + text +
                      "' (auto, hessian, sandwich_hac, block_bootstrap, experiment_bootstrap)");
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
  if (const YAML::Node n = node["runs"]) {
    u.bootstrap.runs = reader.Int(n, Child(path, "runs"));
    if (u.bootstrap.runs < kMinBootstrapRuns) {
      reader.Fail(n, Child(path, "runs"), "must be >= " + std::to_string(kMinBootstrapRuns));
    }
  }
  if (const YAML::Node n = node["block_length"]) {
    const std::string key = Child(path, "block_length");
    if (n.IsScalar() && n.Scalar() == "auto") {
      u.bootstrap.block_length = 0.0;
    } else {
      u.bootstrap.block_length = reader.Double(n, key);
      if (!(u.bootstrap.block_length > 0.0)) reader.Fail(n, key, "must be auto or > 0 (seconds)");
    }
  }
  if (const YAML::Node n = node["input_noise"]) {
    const std::string key = Child(path, "input_noise");
    const std::string text = n.IsScalar() ? n.Scalar() : "";
    if (text != "auto" && text != "off" && text != "true" && text != "false") {
      reader.Fail(n, key, "must be auto or off (true or false)");
    }
    u.input_noise = text == "auto" || text == "true";
  }
  if (const YAML::Node n = node["input_noise_runs"]) {
    u.input_noise_runs = reader.Int(n, Child(path, "input_noise_runs"));
    if (u.input_noise_runs < kMinInputNoiseRuns) {
      reader.Fail(n, Child(path, "input_noise_runs"),
                  "must be >= " + std::to_string(kMinInputNoiseRuns));
    }
  }
  if (const YAML::Node n = node["seed"]) {
    const int seed = reader.Int(n, Child(path, "seed"));
    if (seed < 0) reader.Fail(n, Child(path, "seed"), "must be >= 0");
    u.bootstrap.seed = static_cast<unsigned>(seed);
  }
}

void CheckBootstrapExperiments(const YamlReader& reader, const YAML::Node& node,
                               const std::string& path, const RunConfig& config,
                               const StageConfig& stage) {
  if (stage.options.uncertainty.method != UncertaintyMethod::kExperimentBootstrap) return;
  int count = 0;
  for (const std::string& name : stage.experiments) {
    for (const ExperimentSpec& e : config.experiments) {
      if (e.name != name) continue;
      // Cut into pieces: the count is known only when the data are read.
      if (e.segment_length > 0.0 || !e.segments.column.empty() || !e.input_range.empty()) return;
      ++count;
    }
  }
  if (count < kMinBootstrapExperiments) {
    reader.Fail(node["method"], Child(path, "method"),
                ExperimentBootstrapRefusal(stage.options.name, count));
  }
}

}  // namespace vesselid

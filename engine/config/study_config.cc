// The config's `study` section (study_options.h), checked against the run's stages and model.
#include <algorithm>

#include "engine/config/config_sections.h"
#include "engine/study/partition_study.h"

namespace vesselid {
namespace {

// The stage the name at `n` (key `key`) names, which must be of the required kind.
const StageConfig& NamedStage(const YamlReader& reader, const YAML::Node& n,
                              const std::string& key, const RunConfig& config,
                              StageConfig::Kind kind) {
  const std::string name = reader.String(n, key);
  const StageConfig* found = nullptr;
  for (const StageConfig& s : config.stages) {
    if (s.options.name == name) found = &s;
  }
  if (found == nullptr) reader.Fail(n, key, "no stage named '" + name + "'");
  if (found->kind != kind) {
    reader.Fail(n, key, "stage '" + name + "' is not a " + StageKindToString(kind) + " stage");
  }
  return *found;
}

// The stage a part studies: `stage` if given (of the required kind), else the last such one.
const StageConfig& StudiedStage(const YamlReader& reader, const YAML::Node& node,
                                const std::string& path, const RunConfig& config,
                                StageConfig::Kind kind, std::string* name) {
  if (const YAML::Node n = node["stage"]) {
    const StageConfig& stage = NamedStage(reader, n, Child(path, "stage"), config, kind);
    *name = stage.options.name;
    return stage;
  }
  const StageConfig* found = nullptr;
  for (const StageConfig& s : config.stages) {
    if (s.kind == kind) found = &s;
  }
  if (found == nullptr) {
    reader.Fail(node, path, std::string("the run has no ") + StageKindToString(kind) + " stage to study");
  }
  return *found;
}

double Confidence(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                  double value) {
  reader.Read(node, path, "confidence", &value);
  if (!(value > 0.0 && value < 1.0)) {
    reader.Fail(node["confidence"], Child(path, "confidence"), "must be in (0, 1)");
  }
  return value;
}

// A count of study cases: at least 1, at most limits.study_cases.
int Positive(const YamlReader& reader, const YAML::Node& node, const std::string& path,
             const std::string& key, int value) {
  reader.Read(node, path, key, &value);
  if (value < 1) reader.Fail(node[key], Child(path, key), "must be >= 1");
  reader.CheckLimit(node[key], Child(path, key), value, reader.limits().study_cases,
                    "limits.study_cases");
  return value;
}

//   profile: {stage | stages, parameters, points, span, confidence}
ProfileOptions ReadProfile(const YamlReader& reader, const YAML::Node& node,
                           const RunConfig& config) {
  const std::string path = "study.profile";
  reader.CheckMap(node, path, {"stage", "stages", "parameters", "points", "span", "confidence"});
  ProfileOptions profile;
  if (node["stage"] && node["stages"]) {
    reader.Fail(node["stages"], Child(path, "stages"), "give stage or stages, not both");
  }
  std::vector<const StageConfig*> stages;
  if (const YAML::Node n = node["stages"]) {
    profile.stages = reader.Strings(n, Child(path, "stages"));
    for (size_t i = 0; i < profile.stages.size(); ++i) {
      stages.push_back(&NamedStage(reader, n[i], Child(Child(path, "stages"), i), config,
                                   StageConfig::Kind::kOutputError));
    }
  } else {
    std::string name;
    stages.push_back(
        &StudiedStage(reader, node, path, config, StageConfig::Kind::kOutputError, &name));
    if (node["stage"]) profile.stages.push_back(name);
  }
  if (const YAML::Node n = node["parameters"]) {
    profile.parameters = reader.Strings(n, Child(path, "parameters"));
    for (const StageConfig* stage : stages) {
      for (size_t i = 0; i < profile.parameters.size(); ++i) {
        bool free = false;
        for (const ParameterSpec& spec : stage->parameters) {
          free |= spec.name == profile.parameters[i] && IsEstimatedOnce(spec.role);
        }
        if (!free) {
          reader.Fail(n[i], Child(Child(path, "parameters"), i),
                      "'" + profile.parameters[i] + "' is not a free parameter of stage '" +
                          stage->options.name + "'");
        }
      }
    }
  }
  profile.points = Positive(reader, node, path, "points", profile.points);
  if (profile.points < 3 || profile.points % 2 == 0) {
    reader.Fail(node["points"], Child(path, "points"),
                "must be odd and >= 3 (the optimum is the middle point)");
  }
  reader.Read(node, path, "span", &profile.span);
  if (!(profile.span > 0.0)) reader.Fail(node["span"], Child(path, "span"), "must be > 0");
  profile.confidence = Confidence(reader, node, path, profile.confidence);
  return profile;
}

// "file:line: key" of `node`, for messages of what the study finds later.
std::string Where(const YamlReader& reader, const YAML::Node& node, const std::string& key) {
  const YAML::Mark mark = node.Mark();
  return reader.file() + (mark.line >= 0 ? ":" + std::to_string(mark.line + 1) : "") + ": " + key;
}

// Monte Carlo noise: per model output, or per model input that every experiment of the stage
// maps to a recorded column (the logged input is what gets the noise).
void CheckMonteCarloNoise(const YamlReader& reader, const YAML::Node& node,
                          const std::string& path, const RunConfig& config,
                          const StageConfig& stage, const std::map<std::string, double>& noise) {
  const ModelInfo& info = config.StageModel(stage).info();
  for (const auto& [name, sd] : noise) {
    const std::string key = Child(path, name);
    if (info.OutputIndex(name) < 0 && info.InputIndex(name) < 0) {
      reader.Fail(node, key,
                  "unknown output or input '" + name + "' (model " + info.name +
                      " has outputs " + JoinNames(info.outputs) + "; inputs " +
                      JoinNames(info.inputs) + ")");
    }
    if (!(sd >= 0.0)) reader.Fail(node, key, "must be >= 0");
    if (info.OutputIndex(name) >= 0) continue;
    for (const std::string& experiment : stage.experiments) {
      const ExperimentSpec* spec = config.FindExperiment(experiment);
      if (spec != nullptr && spec->inputs.count(name) == 0) {
        reader.Fail(node, key,
                    "input '" + name + "' is not recorded in experiment '" + experiment +
                        "' (no column maps it), so it has no logged values to add noise to");
      }
    }
  }
}

//   monte_carlo: {stage, runs, noise: {<output or input>: sd},
//                 truth: {<parameter>: value} | estimate, start: stage|truth, confidence}
MonteCarloOptions ReadMonteCarlo(const YamlReader& reader, const YAML::Node& node,
                                 const RunConfig& config, const YAML::Node& simulation) {
  const std::string path = "study.monte_carlo";
  reader.CheckMap(node, path, {"stage", "runs", "noise", "truth", "start", "confidence"});
  MonteCarloOptions mc;
  const StageConfig& stage =
      StudiedStage(reader, node, path, config, StageConfig::Kind::kOutputError, &mc.stage);
  const ModelInfo& info = config.StageModel(stage).info();
  mc.runs = Positive(reader, node, path, "runs", mc.runs);
  // truth: estimate - a parametric bootstrap around the stage's own estimate.
  const YAML::Node given = node["truth"];
  mc.truth_estimate = given && given.IsScalar() && given.as<std::string>() == "estimate";
  if (mc.truth_estimate) mc.truth_where = Where(reader, given, Child(path, "truth"));
  if (given && given.IsScalar() && !mc.truth_estimate) {
    reader.Fail(given, Child(path, "truth"),
                "expected {<parameter>: value} or estimate, got '" + given.as<std::string>() +
                    "'");
  }
  if (node["noise"]) {
    mc.noise = reader.DoubleMap(node["noise"], Child(path, "noise"));
    CheckMonteCarloNoise(reader, node["noise"], Child(path, "noise"), config, stage, mc.noise);
  } else if (!mc.truth_estimate) {
    reader.Fail(node, path,
                "missing key 'noise' ({<output or input>: sd}; only truth: estimate takes the "
                "fit's residual SD)");
  }
  // The truth: study's own, else the simulation's (the parameters the data were made with).
  // (Copy-constructed once: YAML::Node's operator= would write through to the node.)
  const bool simulated = !given && simulation.IsMap() && simulation["truth"];
  const YAML::Node truth = simulated ? simulation["truth"] : given;
  const std::string truth_path = simulated ? "simulation.truth" : Child(path, "truth");
  if (!truth) reader.Fail(node, path, "missing key 'truth' (and no simulation.truth)");
  if (!mc.truth_estimate) {
    mc.truth = reader.DoubleMap(truth, truth_path);
    for (const auto& [name, value] : mc.truth) {
      if (info.ParameterIndex(name) < 0) {
        reader.Fail(truth, Child(truth_path, name),
                    "unknown parameter '" + name + "' (model " + info.name + ")");
      }
    }
    for (const ParameterSpec& spec : stage.parameters) {
      if (IsEstimatedOnce(spec.role) && mc.truth.count(spec.name) == 0) {
        reader.Fail(truth, truth_path, "no value for free parameter '" + spec.name + "'");
      }
    }
  }
  if (const YAML::Node n = node["start"]) {
    const std::string start = reader.String(n, Child(path, "start"));
    if (start != "stage" && start != "truth") {
      reader.Fail(n, Child(path, "start"), "expected stage or truth, got '" + start + "'");
    }
    mc.start_at_truth = start == "truth";
  }
  mc.confidence = Confidence(reader, node, path, mc.confidence);
  return mc;
}

//   starts: {stage, runs, sampling: uniform|log, spread, global: {...}, tolerance}
StartPointOptions ReadStarts(const YamlReader& reader, const YAML::Node& node,
                             const RunConfig& config) {
  const std::string path = "study.starts";
  reader.CheckMap(node, path, {"stage", "runs", "sampling", "spread", "global", "tolerance"});
  StartPointOptions starts;
  const StageConfig& stage =
      StudiedStage(reader, node, path, config, StageConfig::Kind::kOutputError, &starts.stage);
  starts.runs = Positive(reader, node, path, "runs", starts.runs);
  if (const YAML::Node n = node["sampling"]) {
    const std::string sampling = reader.String(n, Child(path, "sampling"));
    if (sampling != "uniform" && sampling != "log") {
      reader.Fail(n, Child(path, "sampling"), "expected uniform or log, got '" + sampling + "'");
    }
    starts.log_sampling = sampling == "log";
  }
  reader.Read(node, path, "spread", &starts.spread);
  if (node["spread"] && !(starts.spread > 1.0)) {
    reader.Fail(node["spread"], Child(path, "spread"), "must be > 1 (a factor around the optimum)");
  }
  starts.global = stage.options.global;
  if (const YAML::Node n = node["global"]) {
    ReadGlobal(reader, n, Child(path, "global"), &starts.global);
    starts.global_given = true;
  }
  reader.Read(node, path, "tolerance", &starts.tolerance);
  if (!(starts.tolerance > 0.0)) {
    reader.Fail(node["tolerance"], Child(path, "tolerance"), "must be > 0");
  }
  return starts;
}

//   partitions: {stage, experiments, repetitions, validation_share, training_shares, methods}
StudyOptions ReadPartitions(const YamlReader& reader, const YAML::Node& node,
                            const RunConfig& config) {
  const std::string path = "study.partitions";
  reader.CheckMap(node, path,
                  {"stage", "experiments", "repetitions", "validation_share", "training_shares",
                   "methods"});
  StudyOptions study;
  // Any stage: a least-squares or an output-error one (partition_study.h).
  if (const YAML::Node n = node["stage"]) {
    study.stage = reader.String(n, Child(path, "stage"));
    if (PartitionStudyStage(config, study.stage) == nullptr) {
      reader.Fail(n, Child(path, "stage"), "no stage named '" + study.stage + "'");
    }
  } else if (PartitionStudyStage(config, "") == nullptr) {
    reader.Fail(node, path, "the run has no stage to study");
  }
  if (node["experiments"]) {
    study.experiments =
        ExperimentNames(reader, node["experiments"], Child(path, "experiments"), config);
  }
  study.partitions = Positive(reader, node, path, "repetitions", study.partitions);
  reader.Read(node, path, "validation_share", &study.validation_share);
  if (!(study.validation_share > 0.0 && study.validation_share < 1.0)) {
    reader.Fail(node["validation_share"], Child(path, "validation_share"), "must be in (0, 1)");
  }
  if (const YAML::Node n = node["training_shares"]) {
    study.training_shares = reader.Doubles(n, Child(path, "training_shares"));
    for (size_t i = 0; i < study.training_shares.size(); ++i) {
      const double share = study.training_shares[i];
      if (!(share > 0.0 && study.validation_share + share <= 1.0 + 1e-9)) {
        reader.Fail(n[i], Child(Child(path, "training_shares"), i),
                    "must be > 0 with validation_share + share <= 1");
      }
    }
  }
  if (const YAML::Node n = node["methods"]) {
    study.methods = reader.Strings(n, Child(path, "methods"));
    if (study.methods.empty()) {
      reader.Fail(n, Child(path, "methods"), "expected segments and/or points");
    }
    for (size_t i = 0; i < study.methods.size(); ++i) {
      if (study.methods[i] != "segments" && study.methods[i] != "points") {
        reader.Fail(n[i], Child(Child(path, "methods"), i),
                    "unknown method '" + study.methods[i] + "' (segments, points)");
      }
    }
  }
  std::string error;
  if (!study.IsValid(&error)) reader.Fail(node, path, error);
  return study;
}

}  // namespace

//   study: {seed, threads, profile, monte_carlo, starts, partitions}
StudyConfig ReadStudy(const YamlReader& reader, const YAML::Node& node, const RunConfig& config,
                      const YAML::Node& simulation) {
  const std::string path = "study";
  reader.CheckMap(node, path,
                  {"seed", "threads", "profile", "monte_carlo", "starts", "partitions"});
  StudyConfig study;
  int seed = static_cast<int>(study.seed);
  reader.Read(node, path, "seed", &seed);
  if (seed < 0) reader.Fail(node["seed"], Child(path, "seed"), "must be >= 0");
  study.seed = static_cast<unsigned>(seed);
  reader.Read(node, path, "threads", &study.execution.threads);
  if (study.execution.threads < 0) {
    reader.Fail(node["threads"], Child(path, "threads"), "must be >= 0 (0: every core)");
  }
  if (const YAML::Node n = node["profile"]) study.profile = ReadProfile(reader, n, config);
  if (const YAML::Node n = node["monte_carlo"]) {
    study.monte_carlo = ReadMonteCarlo(reader, n, config, simulation);
  }
  if (const YAML::Node n = node["starts"]) study.starts = ReadStarts(reader, n, config);
  if (const YAML::Node n = node["partitions"]) {
    study.partitions = ReadPartitions(reader, n, config);
  }
  return study;
}

}  // namespace vesselid

#include "engine/config/config.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "ceres/types.h"
#include "engine/config/config_sections.h"
#include "engine/config/data_folder.h"
#include "engine/config/disturbance_config.h"
#include "engine/config/experiment_data_config.h"
#include "engine/config/experiment_templates.h"
#include "engine/config/input_noise_config.h"
#include "engine/config/model_family.h"
#include "engine/config/simulation_section.h"

namespace vesselid {

namespace {

namespace fs = std::filesystem;

// The config's `simulation` map, or a null node when it has none (what the family's and the
// study's readers refuse, naming the key).
YAML::Node SimulationNode(const ConfigFile& config) {
  return config.simulation ? config.simulation->node : YAML::Node();
}

template <class V>
std::vector<std::string> Keys(const std::map<std::string, V>& map) {
  std::vector<std::string> keys;
  for (const auto& item : map) keys.push_back(item.first);
  return keys;
}

Interpolation ReadInterpolation(const YamlReader& reader, const YAML::Node& node,
                                const std::string& key) {
  Interpolation interpolation;
  if (!StringToInterpolation(reader.String(node, key), &interpolation)) {
    reader.Fail(node, key,
                "unknown interpolation '" + node.Scalar() + "' (zero_order_hold, linear, cubic)");
  }
  return interpolation;
}

// `in_memory`: the names of the experiments whose records the caller hands over (their
// `file` may be absent).
ExperimentSpec ReadExperiment(const YamlReader& reader, const YAML::Node& node,
                              const std::string& path, const fs::path& base, const ModelInfo& info,
                              const std::set<std::string>& in_memory) {
  reader.CheckMap(node, path, ExperimentKeys());
  ExperimentSpec spec;
  if (!node["name"]) reader.Fail(node, path, "missing key 'name'");
  spec.name = reader.Name(node["name"], Child(path, "name"));
  if (node["file"]) {
    const std::string file = reader.String(node["file"], Child(path, "file"));
    spec.file = fs::path(file).is_absolute() ? file : (base / file).lexically_normal().string();
    const std::string outside = OutsideDataFolder(file, base.string(), reader.limits());
    if (!outside.empty()) reader.Fail(node["file"], Child(path, "file"), outside);
    spec.outside_data_folder = DataFolderLeft(file, base.string());
  } else if (in_memory.count(spec.name) == 0) {
    reader.Fail(node, path,
                "missing key 'file' (or 'files', a pattern)" +
                    std::string(in_memory.empty() ? "" : ", and no data given for it"));
  }
  if (const YAML::Node n = node["separator"]) {
    const std::string separator = reader.String(n, Child(path, "separator"));
    if (separator != "," && separator != ";" && separator != "\t") {
      reader.Fail(n, Child(path, "separator"),
                  "expected \",\", \";\" or \"\\t\" (tab), got '" + separator + "'");
    }
    spec.csv.separator = separator[0];
  }
  // bad_cells: the share of a mapped column's cells that may be mangled text (read as gaps).
  spec.csv.max_bad_share = kDefaultBadCellShare;
  reader.Read(node, path, "bad_cells", &spec.csv.max_bad_share);
  if (!(spec.csv.max_bad_share >= 0.0 && spec.csv.max_bad_share < 1.0)) {
    reader.Fail(node["bad_cells"], Child(path, "bad_cells"),
                "must be a share in [0, 1) of a column's cells (0: refuse any)");
  }
  bool inputs_required = false;
  for (size_t i = 0; i < info.inputs.size(); ++i) inputs_required |= !info.InputOptional(static_cast<int>(i));
  if (!node["inputs"] && inputs_required) reader.Fail(node, path, "missing key 'inputs'");
  if (node["inputs"]) {
    spec.inputs = reader.StringMap(node["inputs"], Child(path, "inputs"));
    CheckNames(reader, node["inputs"], Child(path, "inputs"), Keys(spec.inputs), info.inputs,
               "input", info);
  }
  if (!node["outputs"]) reader.Fail(node, path, "missing key 'outputs'");
  spec.outputs = reader.StringMap(node["outputs"], Child(path, "outputs"));
  CheckNames(reader, node["outputs"], Child(path, "outputs"), Keys(spec.outputs), info.outputs,
             "output", info);
  if (const YAML::Node n = node["interpolation"]) {
    const std::string key = Child(path, "interpolation");
    if (n.IsScalar()) {
      spec.default_interpolation = ReadInterpolation(reader, n, key);
    } else {
      reader.CheckMap(n, key, info.inputs);
      for (const auto& item : n) {
        const std::string input = item.first.as<std::string>();
        spec.interpolation[input] = ReadInterpolation(reader, item.second, Child(key, input));
      }
    }
  }
  if (const YAML::Node n = node["weights"]) {
    spec.output_weights = reader.DoubleMap(n, Child(path, "weights"));
    CheckNames(reader, n, Child(path, "weights"), Keys(spec.output_weights), info.outputs, "output",
               info);
    for (const auto& [output, weight] : spec.output_weights) {
      if (!(weight >= 0.0))
        reader.Fail(n[output], Child(Child(path, "weights"), output), "weight must be >= 0");
    }
  }
  if (const YAML::Node n = node["initial_state"]) {
    spec.initial_state = reader.DoubleMap(n, Child(path, "initial_state"));
    CheckNames(reader, n, Child(path, "initial_state"), Keys(spec.initial_state), info.states,
               "state", info);
  }
  if (const YAML::Node n = node["wrap"]) {
    const std::string key = Child(path, "wrap");
    spec.wrapped_outputs = reader.Strings(n, key);
    CheckNames(reader, n, key, spec.wrapped_outputs, info.outputs, "output", info);
    for (size_t i = 0; i < spec.wrapped_outputs.size(); ++i) {
      const int o = info.OutputIndex(spec.wrapped_outputs[i]);
      if (o >= static_cast<int>(info.angle_outputs.size()) || !info.angle_outputs[o]) {
        reader.Fail(
            n[i], Child(key, i),
            "output '" + spec.wrapped_outputs[i] + "' is not an angle; only angles can be wrapped");
      }
    }
  }
  if (const YAML::Node n = node["degrees"])
    spec.degree_columns = reader.Strings(n, Child(path, "degrees"));
  if (const YAML::Node n = node["window"]) {
    std::vector<double> window = reader.Doubles(n, Child(path, "window"));
    if (window.size() != 2 || !(window[0] < window[1])) {
      reader.Fail(n, Child(path, "window"), "expected [t_begin, t_end] with t_begin < t_end");
    }
    spec.t_begin = window[0];
    spec.t_end = window[1];
  }
  reader.Read(node, path, "segment_length", &spec.segment_length);
  if (!(spec.segment_length >= 0.0)) {
    reader.Fail(node["segment_length"], Child(path, "segment_length"), "must be >= 0");
  }
  if (const YAML::Node n = node["segments"]) {
    const std::string key = Child(path, "segments");
    reader.CheckMap(n, key, {"column", "take", "validation_share", "seed"});
    if (!n["column"]) reader.Fail(n, key, "missing key 'column'");
    SegmentSelection& s = spec.segments;
    s.column = reader.String(n["column"], Child(key, "column"));
    if (n["take"] && !StringToTake(reader.String(n["take"], Child(key, "take")), &s.take)) {
      reader.Fail(n["take"], Child(key, "take"), "expected all, training or validation");
    }
    reader.Read(n, key, "validation_share", &s.validation_share);
    if (!(s.validation_share >= 0.0 && s.validation_share <= 1.0)) {
      reader.Fail(n["validation_share"], Child(key, "validation_share"), "must be in [0, 1]");
    }
    int seed = static_cast<int>(s.seed);
    reader.Read(n, key, "seed", &seed);
    s.seed = static_cast<unsigned>(seed);
    if (spec.segment_length > 0.0) {
      reader.Fail(n, key, "segments and segment_length cannot be combined");
    }
  }
  //   input_range: {<input>: [lower, upper], ..., min_duration: 10, skip: 0}
  if (const YAML::Node n = node["input_range"]) {
    const std::string key = Child(path, "input_range");
    std::vector<std::string> allowed = info.inputs;
    allowed.insert(allowed.end(), {"min_duration", "skip"});
    reader.CheckMap(n, key, allowed);
    reader.Read(n, key, "min_duration", &spec.input_range_min_duration);
    reader.Read(n, key, "skip", &spec.input_range_skip);
    if (!(spec.input_range_min_duration >= 0.0) || !(spec.input_range_skip >= 0.0)) {
      reader.Fail(n, key, "min_duration and skip must be >= 0");
    }
    for (const std::string& input : info.inputs) {
      if (!n[input]) continue;
      if (spec.inputs.count(input) == 0) {
        reader.Fail(n[input], Child(key, input), "input '" + input + "' is not mapped to a column");
      }
      const std::vector<double> range = reader.Doubles(n[input], Child(key, input));
      if (range.size() != 2 || !(range[0] <= range[1])) {
        reader.Fail(n[input], Child(key, input), "expected [lower, upper] with lower <= upper");
      }
      spec.input_range[input] = {range[0], range[1]};
    }
    if (spec.input_range.empty()) reader.Fail(n, key, "no input listed");
  }
  // A given initial state is the record's start (with segment_length: its first piece's).
  // Segments and input-range stretches each start somewhere else.
  for (const char* cut : {"segments", "input_range"}) {
    if (node["initial_state"] && node[cut]) {
      reader.Fail(node["initial_state"], Child(path, "initial_state"),
                  std::string("cannot be combined with '") + cut +
                      "': each segment starts from its own state; estimate it with the "
                      "stage's free_initial_states");
    }
  }
  if (const YAML::Node n = node["input_noise"]) {
    ReadInputNoise(reader, n, Child(path, "input_noise"), info, &spec);
  }
  ReadExperimentData(reader, node, path, info, &spec);  // time, position, screen, resample
  return spec;
}

ParameterSpec ReadParameter(const YamlReader& reader, const YAML::Node& node,
                            const std::string& path, const std::string& name) {
  ParameterSpec spec;
  spec.name = name;
  if (node.IsScalar()) {
    spec.start = reader.Double(node, path);
  } else {
    reader.CheckMap(node, path, {"start", "lower", "upper", "scale", "role"});
    if (node["start"]) {
      spec.start = reader.Double(node["start"], Child(path, "start"));
    } else {
      spec.start_from_previous = true;
    }
    reader.Read(node, path, "lower", &spec.lower);
    reader.Read(node, path, "upper", &spec.upper);
    reader.Read(node, path, "scale", &spec.scale);
    if (node["role"]) {
      const std::string role = reader.String(node["role"], Child(path, "role"));
      if (!StringToParameterRole(role, &spec.role)) {
        reader.Fail(node["role"], Child(path, "role"),
                    "unknown role '" + role + "' (free, fixed, per_experiment, isolated, shared)");
      }
    }
  }
  std::string error;
  if (!spec.IsValid(reader.file(), &error)) {
    reader.Fail(node, path, error.substr(reader.file().size() + 2));
  }
  return spec;
}

void ReadLocal(const YamlReader& reader, const YAML::Node& node, const std::string& path,
               LocalSolveOptions* local) {
  reader.CheckMap(node, path,
                  {"trust_region", "linear_solver", "max_iterations", "function_tolerance",
                   "gradient_tolerance", "parameter_tolerance", "max_time", "num_threads",
                   "initial_radius"});
  if (node["trust_region"]) {
    std::string text = reader.String(node["trust_region"], Child(path, "trust_region"));
    if (!StringToTrustRegion(text, &local->trust_region)) {
      reader.Fail(node["trust_region"], Child(path, "trust_region"),
                  "unknown trust region '" + text +
                      "' (levenberg_marquardt, dogleg, reflective)");
    }
  }
  if (node["linear_solver"]) {
    std::string text = reader.String(node["linear_solver"], Child(path, "linear_solver"));
    ceres::LinearSolverType type;
    if (ceres::StringToLinearSolverType(text, &type)) {
      local->linear_solver = type;
    } else {
      reader.Fail(node["linear_solver"], Child(path, "linear_solver"),
                  "unknown linear solver '" + text +
                      "' (dense_qr, dense_normal_cholesky, sparse_normal_cholesky, dense_schur, "
                      "sparse_schur, iterative_schur, cgnr)");
    }
  }
  reader.Read(node, path, "max_iterations", &local->max_iterations);
  if (node["initial_radius"]) {
    double radius = 0.0;
    reader.Read(node, path, "initial_radius", &radius);
    local->initial_radius = radius;
  }
  reader.Read(node, path, "function_tolerance", &local->function_tolerance);
  reader.Read(node, path, "gradient_tolerance", &local->gradient_tolerance);
  reader.Read(node, path, "parameter_tolerance", &local->parameter_tolerance);
  reader.Read(node, path, "max_time", &local->max_time_seconds);
  reader.Read(node, path, "num_threads", &local->num_threads);
  std::string error;
  if (!local->IsValid(&error)) reader.Fail(node, path, error);
}


//   least_squares: {penalty: none|ridge|lasso, lambda, folds, robust,
//                   regions: {<state>: [<region>...]}, grid, smoothing: {half_width, order},
//                   max_profile_evaluations, bootstrap: runs | {runs, lambda, seed, blocks}}
void ReadLeastSquares(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                      const ModelHandle& model, StageConfig* stage) {
  reader.CheckMap(node, path, {"penalty", "lambda", "folds", "robust", "regions", "grid",
                               "smoothing", "max_gap", "max_profile_evaluations", "bootstrap"});
  const RegressionForm* form = model.regression_form();
  const ModelInfo& info = model.info();
  if (form == nullptr) reader.Fail(node, path, "model " + info.name + " has no equation-error form");
  LeastSquaresOptions& ls = stage->least_squares;
  if (node["penalty"]) {
    const std::string penalty = reader.String(node["penalty"], Child(path, "penalty"));
    if (penalty == "none") ls.regression.penalty = Penalty::kNone;
    else if (penalty == "ridge") ls.regression.penalty = Penalty::kRidge;
    else if (penalty == "lasso") ls.regression.penalty = Penalty::kLasso;
    else reader.Fail(node["penalty"], Child(path, "penalty"), "expected none, ridge or lasso");
  }
  reader.Read(node, path, "lambda", &ls.regression.lambda);
  reader.Read(node, path, "folds", &ls.regression.folds);
  if (ls.regression.folds < 2) reader.Fail(node["folds"], Child(path, "folds"), "must be >= 2");
  reader.Read(node, path, "robust", &ls.regression.robust);
  reader.Read(node, path, "max_profile_evaluations", &ls.max_profile_evaluations);
  // The lasso's estimates have no analytic covariance: bootstrapped unless asked otherwise.
  if (ls.regression.penalty == Penalty::kLasso) ls.bootstrap.runs = 200;
  if (const YAML::Node bootstrap = node["bootstrap"]) {
    ReadBootstrap(reader, bootstrap, Child(path, "bootstrap"), true, &ls.bootstrap);
  }
  if (const YAML::Node regions = node["regions"]) {
    const std::string key = Child(path, "regions");
    std::vector<std::string> states;
    for (int s : form->states) states.push_back(info.states[s]);
    reader.CheckMap(regions, key, states);
    ls.regions.assign(states.size(), {});
    for (size_t i = 0; i < states.size(); ++i) {
      const YAML::Node list = regions[states[i]];
      if (!list) continue;
      const std::vector<std::string> names = reader.Strings(list, Child(key, states[i]));
      for (size_t j = 0; j < names.size(); ++j) {
        auto found = std::find(form->regions.begin(), form->regions.end(), names[j]);
        if (found == form->regions.end()) {
          reader.Fail(list[j], Child(Child(key, states[i]), j),
                      "unknown region '" + names[j] + "' (" + JoinNames(form->regions) + ")");
        }
        ls.regions[i].push_back(static_cast<int>(found - form->regions.begin()));
      }
    }
  }
  ReadRegressionData(reader, node, path, info, &stage->regression_data);
}

// `node` and everything in it in flow style ("[a, b]" whether a file wrote a block list or a
// Python dict gave a JSON one).
void SetFlowStyle(YAML::Node node) {
  if (!node.IsSequence() && !node.IsMap()) return;
  node.SetStyle(YAML::EmitterStyle::Flow);
  for (auto item : node) {
    SetFlowStyle(node.IsMap() ? item.second : YAML::Node(item));
  }
}

// The `model` map's keys but family, each value in YAML flow style.
ModelOptions OptionsText(const YAML::Node& model) {
  ModelOptions options;
  for (const auto& item : model) {
    const std::string key = item.first.as<std::string>();
    if (key == "family") continue;
    const YAML::Node value = YAML::Clone(item.second);
    SetFlowStyle(value);
    YAML::Emitter text;
    text << YAML::Flow << value;
    options[key] = text.c_str();
  }
  return options;
}

// The run's model map with the keys of `override` replaced, built by the family; `options`
// gets the merged map's (OptionsText).
std::shared_ptr<const ModelHandle> OverrideModel(const YamlReader& reader,
                                                 const ModelFamily& family,
                                                 const YAML::Node& base,
                                                 const YAML::Node& override,
                                                 const std::string& path, ModelOptions* options) {
  if (!override.IsMap()) reader.Fail(override, path, "expected a map of model keys");
  YAML::Node merged = YAML::Clone(base);
  for (const auto& item : override) {
    const std::string key = reader.KeyName(item.first, path);
    if (key == "family") reader.Fail(item.first, Child(path, key), "a stage cannot change the family");
    merged[key] = item.second;
  }
  *options = OptionsText(merged);
  return family.make_model(reader, merged, path);
}

// A list of experiment names at `key`, each one the config defines.

//   per_experiment: fit | hold (final_validation), validation_per_experiment (a stage)
HeldOutPerExperiment ReadHeldOutPerExperiment(const YamlReader& reader, const YAML::Node& node,
                                              const std::string& key) {
  const std::string text = reader.String(node, key);
  HeldOutPerExperiment mode = HeldOutPerExperiment::kFit;
  if (!StringToHeldOutPerExperiment(text, &mode)) {
    reader.Fail(node, key, "unknown choice '" + text + "' (fit, hold)");
  }
  return mode;
}

//   initial_state_prior: segments | all | off, or {apply: ..., scale: 1, bounds: 3}
InitialStatePrior ReadInitialStatePrior(const YamlReader& reader, const YAML::Node& n,
                                        const std::string& key) {
  InitialStatePrior prior;
  auto read_apply = [&](const YAML::Node& value, const std::string& where) {
    const std::string text = reader.String(value, where);
    if (text == "segments")
      prior.apply = InitialStatePrior::Apply::kSegments;
    else if (text == "all")
      prior.apply = InitialStatePrior::Apply::kAll;
    else if (text == "off")
      prior.apply = InitialStatePrior::Apply::kOff;
    else
      reader.Fail(value, where, "expected segments, all or off");
  };
  if (n.IsScalar()) {
    read_apply(n, key);
  } else {
    reader.CheckMap(n, key, {"apply", "scale", "bounds"});
    if (n["apply"]) read_apply(n["apply"], Child(key, "apply"));
    reader.Read(n, key, "scale", &prior.scale);
    reader.Read(n, key, "bounds", &prior.bounds);
    if (!(prior.scale > 0.0)) reader.Fail(n["scale"], Child(key, "scale"), "must be > 0");
    if (!(prior.bounds >= 0.0)) reader.Fail(n["bounds"], Child(key, "bounds"), "must be >= 0");
  }
  return prior;
}

//   held_out: {start: measured | refitted, burn_in: <s>, implausible_sds: 5}
void ReadHeldOutStart(const YamlReader& reader, const YAML::Node& n, const std::string& key,
                      HeldOutStart* start) {
  reader.CheckMap(n, key, {"start", "burn_in", "implausible_sds"});
  if (n["start"]) {
    const std::string text = reader.String(n["start"], Child(key, "start"));
    if (!StringToHeldOutStartMode(text, &start->mode)) {
      reader.Fail(n["start"], Child(key, "start"),
                  "unknown choice '" + text + "' (measured, refitted)");
    }
  }
  reader.Read(n, key, "burn_in", &start->burn_in);
  if (!(start->burn_in >= 0.0) || !std::isfinite(start->burn_in)) {
    reader.Fail(n["burn_in"], Child(key, "burn_in"),
                "must be a duration in s >= 0 (0: a tenth of each run)");
  }
  reader.Read(n, key, "implausible_sds", &start->implausible_sds);
  if (!(start->implausible_sds > 0.0)) {
    reader.Fail(n["implausible_sds"], Child(key, "implausible_sds"), "must be > 0");
  }
}

// The stage's type and the parameters it lists (a step-regression stage estimates every
// parameter of the damping-inertia form and holds the rest, so it lists none).
void ReadStageKindAndParameters(const YamlReader& reader, const YAML::Node& node,
                                const std::string& path, const RunConfig& config,
                                const ModelInfo& info, StageConfig* stage) {
  const std::string type =
      node["type"] ? reader.String(node["type"], Child(path, "type")) : "output_error";
  if (!StringToStageKind(type, &stage->kind)) {
    reader.Fail(node["type"], Child(path, "type"),
                "unknown stage type '" + type + "' (output_error, least_squares, step_regression)");
  }
  if (stage->kind == StageConfig::Kind::kStepRegression &&
      config.StageModel(*stage).damping_inertia_form() == nullptr) {
    reader.Fail(node["type"], Child(path, "type"),
                "model " + info.name + " has no damping-inertia form for a step-regression stage");
  }
  const bool lists_parameters = stage->kind != StageConfig::Kind::kStepRegression;
  if (!lists_parameters && node["parameters"]) {
    reader.Fail(node["parameters"], Child(path, "parameters"),
                "a step-regression stage estimates every damping and inertia parameter; list none");
  }
  if (lists_parameters && !node["parameters"]) {
    reader.Fail(node, path, "missing key 'parameters'");
  }
  const YAML::Node parameters = lists_parameters ? node["parameters"] : YAML::Node(YAML::NodeType::Map);
  reader.CheckMap(parameters, Child(path, "parameters"), info.parameters);
  for (const auto& item : parameters) {
    const std::string name = item.first.as<std::string>();
    stage->parameters.push_back(
        ReadParameter(reader, item.second, Child(Child(path, "parameters"), name), name));
  }
}

//   outliers: {action: note | downweight | drop, threshold: 5}
void ReadOutliers(const YamlReader& reader, const YAML::Node& n, const std::string& key,
                  OutlierOptions* outliers) {
  reader.CheckMap(n, key, {"action", "threshold"});
  if (n["action"]) {
    const std::string action = reader.String(n["action"], Child(key, "action"));
    if (action == "note")
      outliers->action = OutlierOptions::Action::kNote;
    else if (action == "downweight")
      outliers->action = OutlierOptions::Action::kDownweight;
    else if (action == "drop")
      outliers->action = OutlierOptions::Action::kDrop;
    else
      reader.Fail(n["action"], Child(key, "action"), "expected note, downweight or drop");
  }
  reader.Read(n, key, "threshold", &outliers->threshold);
  if (!(outliers->threshold > 0.0)) {
    reader.Fail(n["threshold"], Child(key, "threshold"), "must be > 0");
  }
}

// How the stage weighs its residuals: loss: {type, scale}, integration: {max_step},
// normalize_by_length, weights: noise | given (stage_weights.h).
void ReadResidualOptions(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                         StageConfig* stage) {
  if (const YAML::Node loss = node["loss"]) {
    reader.CheckMap(loss, Child(path, "loss"), {"type", "scale"});
    reader.Read(loss, Child(path, "loss"), "type", &stage->problem.loss);
    reader.Read(loss, Child(path, "loss"), "scale", &stage->problem.loss_scale);
    const std::string& t = stage->problem.loss;
    if (t != "none" && t != "huber" && t != "cauchy" && t != "soft_l1" && t != "arctan") {
      reader.Fail(loss["type"], Child(path, "loss.type"),
                  "unknown loss '" + t + "' (none, huber, cauchy, soft_l1, arctan)");
    }
    if (!(stage->problem.loss_scale > 0))
      reader.Fail(loss, Child(path, "loss.scale"), "must be > 0");
  }
  if (const YAML::Node integration = node["integration"]) {
    reader.CheckMap(integration, Child(path, "integration"), {"max_step"});
    reader.Read(integration, Child(path, "integration"), "max_step", &stage->experiment.max_step);
    if (!(stage->experiment.max_step >= 0)) {
      reader.Fail(integration, Child(path, "integration.max_step"), "must be >= 0");
    }
  }
  reader.Read(node, path, "normalize_by_length", &stage->experiment.normalize_by_length);
  stage->normalize_by_length_set = static_cast<bool>(node["normalize_by_length"]);
  if (const YAML::Node n = node["weights"]) {
    const std::string text = reader.String(n, Child(path, "weights"));
    if (text == "noise")
      stage->weights = StageConfig::Weights::kNoise;
    else if (text == "given")
      stage->weights = StageConfig::Weights::kGiven;
    else
      reader.Fail(n, Child(path, "weights"), "unknown choice '" + text + "' (noise, given)");
  }
}

// The sections of the regression stages (least_squares, step_regression), and the keys each
// kind of stage does not use refused.
void ReadRegressionSections(const YamlReader& reader, const YAML::Node& node,
                            const std::string& path, const RunConfig& config, StageConfig* stage) {
  const ModelHandle& model = config.StageModel(*stage);
  if (const YAML::Node ls = node["least_squares"]) {
    ReadLeastSquares(reader, ls, Child(path, "least_squares"), model, stage);
  }
  if (const YAML::Node sr = node["step_regression"]) {
    if (stage->kind != StageConfig::Kind::kStepRegression) {
      reader.Fail(sr, Child(path, "step_regression"), "only for stages of type step_regression");
    }
  }
  if (stage->kind == StageConfig::Kind::kStepRegression) {
    ReadStepRegression(reader, node["step_regression"], Child(path, "step_regression"), model,
                       stage);
    for (const char* key :
         {"loss", "continuation", "global", "least_squares", "free_initial_states",
          "normalize_by_length", "integration", "initial_state_prior", "outliers", "weights",
          "noise"}) {
      if (node[key]) reader.Fail(node[key], Child(path, key), "not used by a step-regression stage");
    }
  }
  if (stage->kind == StageConfig::Kind::kLeastSquares) {
    if (model.regression_form() == nullptr) {
      reader.Fail(node["type"], Child(path, "type"),
                  "model " + model.info().name +
                      " has no equation-error form for a least-squares stage");
    }
    for (const char* key : {"loss", "continuation", "global", "outliers", "weights", "noise"}) {
      if (node[key]) reader.Fail(node[key], Child(path, key), "not used by a least-squares stage");
    }
  }
}

StageConfig ReadStage(const YamlReader& reader, const YAML::Node& node, const std::string& path,
                      const RunConfig& config, const ModelFamily& family,
                      const YAML::Node& model_node, size_t index) {
  reader.CheckMap(
      node, path,
      {"name", "type", "least_squares", "step_regression", "model", "experiments", "validation",
       "validation_per_experiment", "outputs", "parameters", "free_initial_states", "loss",
       "integration", "normalize_by_length", "continuation", "global", "local", "uncertainty",
       "initial_state_prior", "held_out", "outliers", "velocity_validation", "weights",
       "noise"});
  StageConfig stage;
  if (node["model"]) {
    stage.model = OverrideModel(reader, family, model_node, node["model"], Child(path, "model"),
                                &stage.model_options);
  }
  const ModelInfo& info = stage.model ? stage.model->info() : config.model->info();
  stage.options.name = "stage" + std::to_string(index + 1);
  if (node["name"]) stage.options.name = reader.Name(node["name"], Child(path, "name"));
  stage.velocity_validation = config.velocity_validation;
  reader.Read(node, path, "velocity_validation", &stage.velocity_validation);
  if (node["experiments"]) {
    stage.experiments =
        ExperimentNames(reader, node["experiments"], Child(path, "experiments"), config);
  } else {
    for (const ExperimentSpec& e : config.experiments) stage.experiments.push_back(e.name);
  }
  if (stage.experiments.empty()) reader.Fail(node, path, "stage has no experiments");
  if (node["validation"]) {
    stage.validation =
        ExperimentNames(reader, node["validation"], Child(path, "validation"), config);
  }
  if (const YAML::Node mode = node["validation_per_experiment"]) {
    stage.validation_per_experiment =
        ReadHeldOutPerExperiment(reader, mode, Child(path, "validation_per_experiment"));
  }
  if (node["outputs"]) {
    stage.experiment.outputs = reader.Strings(node["outputs"], Child(path, "outputs"));
    CheckNames(reader, node["outputs"], Child(path, "outputs"), stage.experiment.outputs,
               info.outputs, "output", info);
  }
  ReadStageKindAndParameters(reader, node, path, config, info, &stage);
  if (node["free_initial_states"]) {
    const std::string key = Child(path, "free_initial_states");
    stage.problem.free_initial_states = reader.Strings(node["free_initial_states"], key);
    CheckNames(reader, node["free_initial_states"], key, stage.problem.free_initial_states,
               info.states, "state", info);
  }
  if (const YAML::Node n = node["initial_state_prior"]) {
    stage.problem.prior = ReadInitialStatePrior(reader, n, Child(path, "initial_state_prior"));
  }
  stage.held_out.prior = stage.problem.prior;
  if (const YAML::Node n = node["held_out"]) {
    ReadHeldOutStart(reader, n, Child(path, "held_out"), &stage.held_out);
  }
  if (const YAML::Node n = node["outliers"]) {
    ReadOutliers(reader, n, Child(path, "outliers"), &stage.outliers);
  }
  if (const YAML::Node continuation = node["continuation"]) {
    stage.continuation = ReadSegmentLengths(reader, continuation, Child(path, "continuation"));
  }
  ReadResidualOptions(reader, node, path, &stage);
  if (const YAML::Node n = node["noise"]) {
    ReadDisturbance(reader, n, Child(path, "noise"), info, &stage.problem.disturbance);
    if (stage.problem.disturbance.active() && stage.problem.loss != "none") {
      reader.Fail(n, Child(path, "noise"),
                  "the filter-error method's likelihood is Gaussian: no robust loss with it");
    }
    if (stage.problem.disturbance.method == DisturbanceSpec::Method::kFilterError &&
        node["weights"]) {
      reader.Fail(node["weights"], Child(path, "weights"),
                  "the filter-error method (noise.method) estimates each output's noise itself");
    }
  }
  if (node["global"]) {
    stage.options.use_global_start = true;
    ReadGlobal(reader, node["global"], Child(path, "global"), &stage.options.global,
               &stage.search_horizons);
    if (node["global"]["horizons"] && !stage.continuation.empty()) {
      reader.Fail(node["global"]["horizons"], Child(Child(path, "global"), "horizons"),
                  "the stage's continuation sets the segments its global start searches on");
    }
  }
  if (node["local"]) ReadLocal(reader, node["local"], Child(path, "local"), &stage.options.local);
  if (const YAML::Node n = node["uncertainty"]) {
    ReadUncertainty(reader, n, Child(path, "uncertainty"), &stage.options);
    CheckBootstrapExperiments(reader, n, Child(path, "uncertainty"), config, stage);
  }
  ReadRegressionSections(reader, node, path, config, &stage);
  return stage;
}

//   limits: {file_mb, data_values, integration_steps, study_cases, evaluations, files,
//            experiments, outside_data, memory_mb}
WorkLimits ReadLimits(const YamlReader& reader, const YAML::Node& node) {
  const std::string path = "limits";
  reader.CheckMap(node, path,
                  {"file_mb", "data_values", "integration_steps", "study_cases", "evaluations",
                   "files", "experiments", "outside_data", "memory_mb"});
  WorkLimits limits;
  auto read = [&](const char* key, double scale, std::uint64_t* value) {
    if (!node[key]) return;
    const double number = reader.Double(node[key], Child(path, key));
    if (!(number >= 1.0 && number * scale <= 1e18)) {
      reader.Fail(node[key], Child(path, key), "must be between 1 and 1e18");
    }
    *value = static_cast<std::uint64_t>(number * scale);
  };
  read("file_mb", 1024.0 * 1024.0, &limits.file_bytes);
  read("data_values", 1.0, &limits.data_values);
  read("integration_steps", 1.0, &limits.integration_steps);
  read("study_cases", 1.0, &limits.study_cases);
  read("evaluations", 1.0, &limits.evaluations);
  read("files", 1.0, &limits.files);
  read("experiments", 1.0, &limits.experiments);
  read("memory_mb", 1024.0 * 1024.0, &limits.memory_bytes);
  reader.Read(node, path, "outside_data", &limits.outside_data);
  return limits;
}

}  // namespace

bool LoadConfigFile(const std::string& path, const std::string& data_dir,
                    const ModelRegistry& registry, ConfigFile* config, std::string* error,
                    bool read_reference) {
  ConfigSource source;
  source.path = path;
  source.data_dir = data_dir;
  source.read_reference = read_reference;
  return LoadConfig(source, registry, config, error);
}

bool LoadConfig(const ConfigSource& source, const ModelRegistry& registry, ConfigFile* config,
                std::string* error) {
  const std::string& path = source.path;
  const std::string& data_dir = source.data_dir;
  YamlReader reader = source.text.empty() ? YamlReader(path) : YamlReader(path, source.text);
  try {
    const YAML::Node root = reader.Load();
    reader.CheckMap(root, "",
                    {"description", "model", "simulation", "experiment_defaults", "experiments",
                     "sets", "stages", "fusion", "final", "final_validation", "surfaces", "study",
                     "select", "design", "limits", "velocity_validation"});
    ConfigFile file;
    RunConfig& result = file.run;
    result.path = path;
    if (const YAML::Node limits = root["limits"]) result.limits = ReadLimits(reader, limits);
    reader.set_limits(result.limits);
    reader.Read(root, "", "description", &result.description);
    reader.Read(root, "", "velocity_validation", &result.velocity_validation);
    const YAML::Node model = root["model"];
    if (!model) reader.Fail(root, "model", "missing key");
    if (!model.IsMap() || !model["family"])
      reader.Fail(model, "model", "expected a map with 'family'");
    result.family = reader.String(model["family"], "model.family");
    file.family = registry.Find(result.family);
    if (file.family == nullptr) {
      reader.Fail(
          model["family"], "model.family",
          "unknown model family '" + result.family + "' (" + JoinNames(registry.Names()) + ")");
    }
    result.model = file.family->make_model(reader, model, "model");
    result.model_options = OptionsText(model);
    const ModelInfo& info = result.model->info();
    if (root["simulation"]) {
      file.simulation = std::make_shared<const SimulationSection>(SimulationSection{root["simulation"]});
    }

    const fs::path base = data_dir.empty() ? fs::path(path).parent_path() : fs::path(data_dir);
    for (const ExperimentEntry& entry : ExpandExperiments(&reader, root, base.string())) {
      ExperimentSpec spec =
          ReadExperiment(reader, entry.node, entry.path, base, info, source.in_memory);
      if (result.FindExperiment(spec.name) != nullptr) {
        reader.Fail(entry.node["name"], Child(entry.path, "name"),
                    "duplicate experiment name '" + spec.name + "'");
      }
      if (result.experiments.size() >= result.limits.experiments) {
        reader.Fail(entry.node, entry.path,
                    "more than " + std::to_string(result.limits.experiments) +
                        " experiments, the limit (limits.experiments)");
      }
      spec.csv.max_bytes = result.limits.file_bytes;
      spec.csv.max_values = result.limits.data_values;
      result.experiments.push_back(std::move(spec));
    }
    if (const YAML::Node sets = root["sets"]) ReadExperimentSets(reader, sets, &result);
    const YAML::Node stages = root["stages"];
    if (!stages) reader.Fail(root, "stages", "missing key");
    reader.CheckSequence(stages, "stages");
    if (stages.size() == 0) reader.Fail(stages, "stages", "at least one stage is needed");
    for (size_t i = 0; i < stages.size(); ++i) {
      result.stages.push_back(
          ReadStage(reader, stages[i], Child("stages", i), result, *file.family, model, i));
    }
    for (StageConfig& stage : result.stages) {
      stage.experiment.max_steps = result.limits.integration_steps;
    }
    result.final_validation.experiment.max_steps = result.limits.integration_steps;
    if (const YAML::Node fusion = root["fusion"]) {
      const std::string rule = reader.String(fusion, "fusion");
      if (!StringToFusionRule(rule, &result.fusion)) {
        reader.Fail(fusion, "fusion",
                    "unknown rule '" + rule + "' (inverse_variance, mean, information)");
      }
    }
    if (const YAML::Node final = root["final"]) {
      const std::string choice = reader.String(final, "final");
      if (!StringToFinalChoice(choice, &result.final_choice)) {
        reader.Fail(final, "final", "unknown choice '" + choice + "' (best_validation, last)");
      }
    }
    if (const YAML::Node final = root["final_validation"]) {
      reader.CheckMap(final, "final_validation",
                      {"experiments", "outputs", "model", "free_initial_states", "per_experiment",
                       "held_out", "initial_state_prior", "reference"});
      FinalValidationConfig& v = result.final_validation;
      result.has_final_validation = true;
      if (final["model"]) {
        ModelOptions ignored;
        v.model = OverrideModel(reader, *file.family, model, final["model"],
                                "final_validation.model", &ignored);
      }
      const ModelInfo& final_info = v.model ? v.model->info() : info;
      if (!final["experiments"]) reader.Fail(final, "final_validation", "missing key 'experiments'");
      v.experiments =
          ExperimentNames(reader, final["experiments"], "final_validation.experiments", result);
      if (final["outputs"]) {
        v.experiment.outputs = reader.Strings(final["outputs"], "final_validation.outputs");
        CheckNames(reader, final["outputs"], "final_validation.outputs", v.experiment.outputs,
                   final_info.outputs, "output", final_info);
      }
      if (final["per_experiment"]) {
        v.per_experiment = ReadHeldOutPerExperiment(reader, final["per_experiment"],
                                                    "final_validation.per_experiment");
      }
      if (const YAML::Node n = final["initial_state_prior"]) {
        v.held_out.prior = ReadInitialStatePrior(reader, n, "final_validation.initial_state_prior");
      }
      if (const YAML::Node n = final["held_out"]) {
        ReadHeldOutStart(reader, n, "final_validation.held_out", &v.held_out);
      }
      if (const YAML::Node n = final["reference"]) {
        // A run's output folder, relative to the config's own folder.
        const fs::path folder = reader.String(n, "final_validation.reference");
        const fs::path resolved =
            folder.is_absolute() ? folder : fs::path(path).parent_path() / folder;
        std::string why;
        if (!source.read_reference) {
          v.reference.folder = resolved.string();  // not read: no values, not flown
        } else if (!registry.reference_reader()) {
          reader.Fail(n, "final_validation.reference", "no reader of runs' results here");
        } else if (!registry.reference_reader()(resolved.string(), registry, result.family,
                                                final_info, &v.reference, &why)) {
          reader.Fail(n, "final_validation.reference", why);
        }
      }
      if (final["free_initial_states"]) {
        const std::string key = "final_validation.free_initial_states";
        v.free_initial_states = reader.Strings(final["free_initial_states"], key);
        CheckNames(reader, final["free_initial_states"], key, v.free_initial_states,
                   final_info.states, "state", final_info);
      }
    }
    if (const YAML::Node surfaces = root["surfaces"]) {
      result.surfaces = ReadSurfaces(reader, surfaces, *result.model);
    }
    if (const YAML::Node study = root["study"]) {
      file.study = ReadStudy(reader, study, result, SimulationNode(file));
    }
    *config = std::move(file);
    return true;
  } catch (const ConfigError& e) {
    *error = e.what();
    return false;
  } catch (const YAML::Exception& e) {
    *error = path + (e.mark.is_null() ? "" : ":" + std::to_string(e.mark.line + 1)) + ": " + e.msg;
    return false;
  }
}

bool LoadRunConfig(const std::string& path, const std::string& data_dir,
                   const ModelRegistry& registry, RunConfig* config, std::string* error) {
  ConfigFile file;
  if (!LoadConfigFile(path, data_dir, registry, &file, error)) return false;
  *config = std::move(file.run);
  return true;
}

bool SimulateConfig(const ConfigFile& config, const std::string& out_dir, std::string* error,
                    bool check_only) {
  try {
    YamlReader reader(config.run.path);
    reader.set_limits(config.run.limits);
    return config.family->simulate(reader, SimulationNode(config), *config.run.model, out_dir,
                                   check_only, error);
  } catch (const ConfigError& e) {
    *error = e.what();
    return false;
  }
}

}  // namespace vesselid

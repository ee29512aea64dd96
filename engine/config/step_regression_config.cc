// The `step_regression` map of a step-regression stage (step_regression.h):
//
//   step_regression:
//     grid: U                          # regression-data grid and smoothing (as least_squares)
//     smoothing: {half_width: 2, order: 2}
//     steady: {smoothing: 5, band_factor: 2, min_duration: 10, input_tolerance: 1e-6,
//              tolerance: {U: 0.05, r: 0.005}}
//     inputs: {tau_m: [0, 0.6]}        # levels kept for damping samples and steps
//     min_change: {U: 0.2, r: 0.01}    # smallest steady change giving an inertia sample
//     step_fit: {min_time_constant: 0.05, max_time_constant: 300, grid: 200, horizon: 60}
//     zero_straight: true
//     mirror: true
//     turn_weights: true
//     lasso: {path_points: 50, path_ratio: 1e-4}
//     asymptote: {a: [0.25, 0.5, 1, 2, 4], b_points: 13}
//     bootstrap: 200                   # or {runs, lambda: held|selected, seed}
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/config/config_sections.h"

namespace vesselid {
namespace {

// A map keyed by the names at `indices` of `names` (states or inputs), each value read by
// `read` into slot i.
template <class Read>
void ReadPerName(const YamlReader& reader, const YAML::Node& node, const std::string& key,
                 const std::vector<std::string>& names, const std::vector<int>& indices,
                 Read read) {
  std::vector<std::string> allowed;
  for (int i : indices) allowed.push_back(names[i]);
  reader.CheckMap(node, key, allowed);
  for (size_t i = 0; i < allowed.size(); ++i) {
    if (node[allowed[i]]) read(i, node[allowed[i]], Child(key, allowed[i]));
  }
}

}  // namespace

void ReadStepRegression(const YamlReader& reader, const YAML::Node& node,
                        const std::string& path, const ModelHandle& model, StageConfig* stage) {
  const DampingInertiaForm& form = *model.damping_inertia_form();
  const ModelInfo& info = model.info();
  StepRegressionOptions& o = stage->step_regression;
  StepSampleOptions& s = o.samples;
  const size_t n = form.states.size();
  s.steady.tolerance.assign(n, 0.0);
  s.input_lower.assign(n, -std::numeric_limits<double>::infinity());
  s.input_upper.assign(n, std::numeric_limits<double>::infinity());
  s.min_change.resize(n);
  for (size_t i = 0; i < n; ++i) s.min_change[i] = 0.02 * form.scale[i];
  // Grid: the first regressed state's output unless given.
  stage->regression_data.grid_output = info.states[form.states[0]];
  stage->regression_data.smoothing = {2, 2, 0};
  if (!node) return;
  reader.CheckMap(node, path,
                  {"grid", "smoothing", "max_gap", "steady", "inputs", "min_change", "step_fit",
                   "zero_straight", "mirror", "turn_weights", "lasso", "asymptote",
                   "bootstrap"});
  ReadRegressionData(reader, node, path, info, &stage->regression_data);
  if (const YAML::Node steady = node["steady"]) {
    const std::string key = Child(path, "steady");
    reader.CheckMap(steady, key,
                    {"smoothing", "band_factor", "min_duration", "input_tolerance", "tolerance"});
    reader.Read(steady, key, "smoothing", &s.steady.smoothing);
    reader.Read(steady, key, "band_factor", &s.steady.band_factor);
    reader.Read(steady, key, "min_duration", &s.steady.min_duration);
    reader.Read(steady, key, "input_tolerance", &s.steady.input_tolerance);
    if (const YAML::Node tolerance = steady["tolerance"]) {
      ReadPerName(reader, tolerance, Child(key, "tolerance"), info.states, form.states,
                  [&](size_t i, const YAML::Node& v, const std::string& k) {
                    s.steady.tolerance[i] = reader.Double(v, k);
                    if (!(s.steady.tolerance[i] >= 0.0)) reader.Fail(v, k, "must be >= 0");
                  });
    }
    std::string error;
    if (!s.steady.IsValid(&error)) reader.Fail(steady, key, error);
  }
  if (const YAML::Node inputs = node["inputs"]) {
    ReadPerName(reader, inputs, Child(path, "inputs"), info.inputs, form.inputs,
                [&](size_t i, const YAML::Node& v, const std::string& k) {
                  const std::vector<double> range = reader.Doubles(v, k);
                  if (range.size() != 2 || !(range[0] <= range[1])) {
                    reader.Fail(v, k, "expected [lower, upper] with lower <= upper");
                  }
                  s.input_lower[i] = range[0];
                  s.input_upper[i] = range[1];
                });
  }
  if (const YAML::Node change = node["min_change"]) {
    ReadPerName(reader, change, Child(path, "min_change"), info.states, form.states,
                [&](size_t i, const YAML::Node& v, const std::string& k) {
                  s.min_change[i] = reader.Double(v, k);
                  if (!(s.min_change[i] > 0.0)) reader.Fail(v, k, "must be > 0");
                });
  }
  if (const YAML::Node fit = node["step_fit"]) {
    const std::string key = Child(path, "step_fit");
    reader.CheckMap(fit, key, {"min_time_constant", "max_time_constant", "grid", "horizon"});
    reader.Read(fit, key, "min_time_constant", &s.step_fit.min_time_constant);
    reader.Read(fit, key, "max_time_constant", &s.step_fit.max_time_constant);
    reader.Read(fit, key, "grid", &s.step_fit.grid);
    reader.Read(fit, key, "horizon", &s.fit_horizon);
    std::string error;
    if (!s.step_fit.IsValid(&error)) reader.Fail(fit, key, error);
    if (!(s.fit_horizon > 0.0)) reader.Fail(fit["horizon"], Child(key, "horizon"), "must be > 0");
  }
  reader.Read(node, path, "zero_straight", &s.zero_straight);
  reader.Read(node, path, "mirror", &s.mirror);
  reader.Read(node, path, "turn_weights", &s.turn_weights);
  if (const YAML::Node lasso = node["lasso"]) {
    const std::string key = Child(path, "lasso");
    reader.CheckMap(lasso, key, {"path_points", "path_ratio"});
    reader.Read(lasso, key, "path_points", &o.lasso.path_points);
    reader.Read(lasso, key, "path_ratio", &o.lasso.path_ratio);
    if (o.lasso.path_points < 2) reader.Fail(lasso, key, "path_points must be >= 2");
    if (!(o.lasso.path_ratio > 0.0 && o.lasso.path_ratio < 1.0)) {
      reader.Fail(lasso, key, "path_ratio must be in (0, 1)");
    }
  }
  if (const YAML::Node asymptote = node["asymptote"]) {
    const std::string key = Child(path, "asymptote");
    reader.CheckMap(asymptote, key, {"a", "b_points"});
    if (asymptote["a"]) o.asymptote_a = reader.Doubles(asymptote["a"], Child(key, "a"));
    reader.Read(asymptote, key, "b_points", &o.asymptote_b_points);
  }
  if (const YAML::Node bootstrap = node["bootstrap"]) {
    ReadBootstrap(reader, bootstrap, Child(path, "bootstrap"), false, &o.bootstrap);
  }
  std::string error;
  if (!o.IsValid(form, &error)) reader.Fail(node, path, error);
}

SurfaceGrid ReadSurfaces(const YamlReader& reader, const YAML::Node& node,
                        const ModelHandle& model) {
  const std::string path = "surfaces";
  const DampingInertiaForm* form = model.damping_inertia_form();
  if (form == nullptr) {
    reader.Fail(node, path, "model " + model.info().name + " has no damping and inertia terms");
  }
  SurfaceGrid grid;
  const ModelInfo& info = model.info();
  if (!node.IsMap()) reader.Fail(node, path, "expected a map");
  for (int i = 0; i < 2; ++i) {
    if (!node[info.states[form->states[i]]]) {
      reader.Fail(node, path, "missing key '" + info.states[form->states[i]] + "'");
    }
  }
  ReadPerName(reader, node, path, info.states, form->states,
              [&](size_t i, const YAML::Node& v, const std::string& k) {
                // Bounded: the surfaces CSV, points x points rows, is built in memory.
                constexpr double kMaxPoints = 1000;
                const std::vector<double> d = reader.Doubles(v, k);
                if (d.size() != 3 || !(d[0] < d[1]) || d[2] < 2 || d[2] > kMaxPoints ||
                    d[2] != std::floor(d[2])) {
                  reader.Fail(v, k, "expected [lower, upper, points] with lower < upper, "
                                    "2 <= points <= 1000");
                }
                grid.lower[i] = d[0];
                grid.upper[i] = d[1];
                grid.points[i] = static_cast<int>(d[2]);
              });
  return grid;
}

}  // namespace vesselid

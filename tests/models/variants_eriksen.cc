// The Eriksen-Breivik 2-DOF variant on the model's own step campaigns: throttle and rudder
// levels held, position, course, speed and turn rate logged.
#include <cmath>
#include <random>

#include "problems/eriksen2dof/handles.h"
#include "tests/models/model_factory.h"
#include "tests/support/eriksen_data.h"

namespace vesselid::testing {
namespace {

ExperimentSpec Spec(const std::vector<std::string>& outputs) {
  ExperimentSpec spec;
  spec.name = "run";
  spec.inputs = {{"tau_m", "throttle"}, {"tau_delta", "rudder"}};
  const std::map<std::string, std::string> columns = {
      {"N", "n"}, {"E", "e"}, {"chi", "course"}, {"U", "sog"}, {"r", "rot"}};
  for (const std::string& o : outputs) spec.outputs[o] = columns.at(o);
  spec.default_interpolation = Interpolation::kZeroOrderHold;
  return spec;
}

// Three 20 s levels, every output; all 66 parameters 5 % off, zero coefficients given small
// values so that every one matters (the m_r asymptote too).
JacobianCase Jacobian(const ModelHandle& model, const std::vector<double>& truth) {
  const Trajectory data = SimulateRuns(
      model, truth, {{{20, 0.3, 0.2}, {20, 0.5, 0.6}, {20, 0.2, -0.4}}}, 0.5, 0.0, 0.0, 1);
  JacobianCase c;
  c.experiment = Build(Spec({"N", "E", "chi", "U", "r"}), data, model.info());
  c.scales.assign(truth.size(), 1.0);
  c.scales[1] = 2.0;
  c.theta = JacobianPoint(truth, c.scales, 1.05, 0.003, {1.0, -2.0, 0.3, 6.0, 0.1});
  c.theta[model.info().ParameterIndex("m_r.tanh")] = 0.3;
  c.tolerance = 1e-5;
  c.min_columns = static_cast<int>(c.theta.size());
  return c;
}

// One 40 s level sampled every 0.8 s.
Rk4Case Rk4(const ModelHandle& model) {
  const std::vector<double> truth = ReferenceCraft(model.info());
  const Trajectory data = SimulateRuns(model, truth, {{{40, 0.4, 0.5}}}, 0.8, 0.0, 0.0, 1);
  ExperimentSpec spec = Spec({"E", "U", "r"});
  spec.initial_state = {{"U", 2.0}, {"r", -0.2}, {"chi", 0.0}, {"N", 0.0}, {"E", 0.0}};
  return MakeRk4Case(model.info(), spec, data, 0.8 / 256, {0.4, 0.2, 0.1}, 0.4);
}

// Random simultaneous steps of both inputs over the envelope with 0.05 m/s and 0.2 deg/s
// noise, residuals weighted by 1 / noise SD; the 12 non-zero coefficients from +20 / -15 %.
RecoveryCase Recovery(const ModelHandle& model, const std::vector<double>& truth) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> throttle(0.05, 0.6), rudder(-1.0, 1.0), hold(8.0, 30.0);
  std::vector<Level> levels;
  for (int k = 0; k < 60; ++k) levels.push_back({hold(random), throttle(random), rudder(random)});
  const double rot_noise = 0.2 * M_PI / 180.0;
  const Trajectory data = SimulateRuns(model, truth, {levels}, 0.2, 0.05, rot_noise, 5);
  ExperimentSpec spec = Spec({"U", "r"});
  spec.output_weights = {{"U", 1.0 / 0.05}, {"r", 1.0 / rot_noise}};
  RecoveryCase c;
  c.experiments.push_back(Build(spec, data, model.info()));
  const ModelInfo& info = model.info();
  for (size_t i = 0; i < truth.size(); ++i) {
    ParameterSpec s;
    s.name = info.parameters[i];
    s.start = truth[i];
    s.role = ParameterRole::kFixed;
    const bool coefficient =
        s.name.find(".a") == std::string::npos && s.name.find(".b") == std::string::npos;
    if (coefficient && truth[i] != 0.0) {
      s.role = ParameterRole::kFree;
      s.start = truth[i] * (c.free_parameters % 2 == 0 ? 1.2 : 0.85);
      ++c.free_parameters;
    }
    c.specs.push_back(s);
  }
  c.sigmas = 3.0;
  c.max_relative_std_error = 0.2;
  c.residual_sd = 1.0;  // unit-weighted residuals
  c.residual_weight = 1.0 / c.experiments[0].num_samples();
  c.residual_tolerance = 0.05;
  return c;
}

}  // namespace

void AddEriksenVariants(std::vector<ModelVariant>* variants) {
  const eriksen2dof::Model model;
  const std::vector<double> truth = ReferenceCraft(eriksen2dof::MakeHandle(model)->info());
  variants->push_back({"Eriksen2Dof", [model] { return eriksen2dof::MakeHandle(model); }, truth,
                       Jacobian, Rk4, Recovery});
}

}  // namespace vesselid::testing

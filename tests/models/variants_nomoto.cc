// Nomoto variants (first order, second order, Norrbin): a multi-sine heading loop of the
// patrol vessel's steering gear and controller, heading measured.
#include <cmath>

#include "problems/nomoto/closed_loop_simulator.h"
#include "problems/nomoto/handles.h"
#include "tests/models/model_factory.h"
#include "tests/support/nomoto_data.h"

namespace vesselid::testing {
namespace {

nomoto::ClosedLoopOptions Loop(double duration, double heading_noise_deg) {
  nomoto::ClosedLoopOptions loop;
  loop.steering_time_constant = 1.0;
  loop.controller_gain = 0.7;
  loop.duration = duration;
  loop.excitation.type = nomoto::Excitation::Type::kMultisine;
  loop.excitation.amplitude = 25.0 * M_PI / 180.0;
  loop.excitation.periods = {60.0, 23.0, 11.0, 5.0, 2.3};
  loop.heading_noise = heading_noise_deg * M_PI / 180.0;
  loop.seed = 7;
  return loop;
}

// 60 s of the loop, away from the truth, with a non-zero initial state; every parameter and
// initial state affects the heading.
JacobianCase Jacobian(const ModelHandle& model, const std::vector<double>& truth) {
  JacobianCase c;
  c.experiment = MakeExperiment(model, truth, Loop(60.0, 0.0));
  c.scales.assign(truth.size(), 1.0);
  c.scales[0] = 2.0;
  std::vector<double> state;
  for (size_t i = 0; i < model.info().states.size(); ++i) state.push_back(0.01 * (i + 1));
  c.theta = JacobianPoint(truth, c.scales, 1.1, 0.01, state);
  c.tolerance = 1e-6;
  c.min_columns = static_cast<int>(c.theta.size());
  return c;
}

// Heading sampled every 0.8 s; constant rudder after the start so the inputs are exact.
Rk4Case Rk4(const ModelHandle& model) {
  Trajectory data;
  data.source = "step";
  data.names = {"delta", "psi"};
  data.columns.resize(2);
  for (int k = 0; k <= 50; ++k) {
    data.t.push_back(0.8 * k);
    data.columns[0].push_back(0.2);
    data.columns[1].push_back(0.0);
  }
  ExperimentSpec spec;
  spec.name = "step";
  spec.inputs = {{"delta", "delta"}};
  spec.outputs = {{"psi", "psi"}};
  spec.initial_state = {{model.info().states[1], 0.05}};
  return MakeRk4Case(model.info(), spec, data, 0.8 / 512, {0.1, 0.05, 0.025}, 0.35);
}

// 600 s with 0.1 deg heading noise from +-30 %; the bias starts at zero and the first
// (noisy) heading is estimated with the rest. The residual SD estimates the noise.
RecoveryCase Recovery(const ModelHandle& model, const std::vector<double>& truth) {
  RecoveryCase c;
  c.experiments.push_back(MakeExperiment(model, truth, Loop(600.0, 0.1)));
  const ModelInfo& info = model.info();
  for (size_t i = 0; i < truth.size(); ++i) {
    ParameterSpec s = PerturbedSpec(info.parameters[i], truth[i], static_cast<int>(i), 0.3);
    if (s.name == "delta_0") {
      s.start = 0.0;
      s.scale = 0.01;
    }
    c.specs.push_back(s);
  }
  c.options.free_initial_states = {"psi"};
  c.free_parameters = static_cast<int>(truth.size());
  c.sigmas = 3.0;
  c.max_relative_std_error = 0.1;
  c.residual_sd = 0.1 * M_PI / 180.0;
  c.residual_weight = 1.0 / c.experiments[0].num_samples();
  c.residual_tolerance = 0.05;
  return c;
}

ModelVariant Variant(const std::string& name, std::function<std::unique_ptr<ModelHandle>()> make,
                     std::vector<double> truth) {
  return {name, std::move(make), std::move(truth), Jacobian, Rk4, Recovery};
}

}  // namespace

void AddNomotoVariants(std::vector<ModelVariant>* variants) {
  variants->push_back(
      Variant("NomotoFirstOrder", nomoto::MakeFirstOrderHandle, {2.0, -0.17, 0.01}));
  variants->push_back(Variant("NomotoSecondOrder", nomoto::MakeSecondOrderHandle,
                              {2.0875, 0.3179, 0.1830, -0.1724, 0.01}));
  variants->push_back(
      Variant("NomotoNorrbin", nomoto::MakeNorrbinHandle, {2.0, -0.17, 40.0, 0.01}));
}

}  // namespace vesselid::testing

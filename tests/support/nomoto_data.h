// Synthetic Nomoto experiments for tests and benchmarks, made in memory with the seed 003
// closed-loop simulator.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"
#include "engine/solve/parameter.h"
#include "problems/nomoto/closed_loop_simulator.h"

namespace vesselid::testing {

struct SeedVessel {
  std::vector<double> truth;  // T1 T2 T3 K delta_0
  nomoto::ClosedLoopOptions loop;
};

// Seed 003 Table 3 set-ups with the sine excitation of configs/nomoto_*.yaml.
inline SeedVessel CargoVessel() {
  SeedVessel v{{45.0, 6.0, 10.0, 0.09, 0.0}, {}};
  v.loop.steering_time_constant = 5.0;
  v.loop.controller_gain = 0.12;
  v.loop.duration = 6000.0;
  v.loop.excitation.amplitude = 20.0 * M_PI / 180.0;
  v.loop.excitation.periods = {300.0};
  return v;
}

inline SeedVessel PatrolVessel() {
  SeedVessel v{{2.0875, 0.3179, 0.1830, -0.1724, 0.0}, {}};
  v.loop.steering_time_constant = 1.0;
  v.loop.controller_gain = 0.7;
  v.loop.duration = 900.0;
  v.loop.excitation.amplitude = 20.0 * M_PI / 180.0;
  v.loop.excitation.periods = {30.0};
  return v;
}

// The start, 50 % off every parameter (T1 x1.5, T2 / 1.5, T3 x1.5, K / 1.5), with the
// bounds of configs/nomoto_*.yaml: wide, sign of K known.
inline std::vector<ParameterSpec> FiftyPercentOff(const std::vector<double>& truth) {
  const double factor[] = {1.5, 1.0 / 1.5, 1.5, 1.0 / 1.5};
  const char* names[] = {"T1", "T2", "T3", "K"};
  std::vector<ParameterSpec> specs;
  for (int i = 0; i < 4; ++i) {
    ParameterSpec s;
    s.name = names[i];
    s.start = truth[i] * factor[i];
    s.lower = i == 3 ? (truth[3] > 0 ? 0.001 : -2.0) : (i == 2 ? 0.0 : 0.01);
    s.upper = i == 3 ? (truth[3] > 0 ? 1.0 : -0.001) : 10 * truth[0];
    specs.push_back(s);
  }
  return specs;
}

// Two minutes at 20 Hz under a gain-0.7 autopilot, a 0.3 rad sine of `period` seconds on the
// heading command: enough for a quick vessel (T ~ 2 s).
inline nomoto::ClosedLoopOptions ShortLoop(double period, unsigned seed) {
  nomoto::ClosedLoopOptions loop;
  loop.controller_gain = 0.7;
  loop.duration = 120.0;
  loop.sample_time = 0.05;
  loop.excitation.amplitude = 0.3;
  loop.excitation.periods = {period};
  loop.seed = seed;
  return loop;
}

// Simulates `loop` with `model` and prepares the experiment comparing psi (delta as input).
inline Experiment MakeExperiment(const ModelHandle& model, const std::vector<double>& truth,
                                 const nomoto::ClosedLoopOptions& loop,
                                 Interpolation interpolation = Interpolation::kCubic,
                                 const std::string& name = "run") {
  Trajectory trajectory;
  std::string error;
  if (!nomoto::SimulateClosedLoop(model, truth, loop, &trajectory, &error)) {
    throw std::runtime_error(error);
  }
  trajectory.source = name;
  ExperimentSpec spec;
  spec.name = name;
  spec.inputs = {{"delta", "delta"}};
  if (model.info().InputIndex("U") >= 0) spec.inputs["U"] = "U";
  spec.outputs = {{"psi", "psi"}};
  spec.default_interpolation = interpolation;
  Experiment experiment;
  if (!BuildExperiment(spec, trajectory, model.info(), ExperimentOptions(), &experiment, &error)) {
    throw std::runtime_error(error);
  }
  return experiment;
}

}  // namespace vesselid::testing

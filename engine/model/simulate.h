// Simulation of one prepared experiment: RK4 from node to node over the whole record,
// handing the state at every node to a visitor (which forms outputs and residuals).
// This is the hot path: no allocation, no virtual call, no lookup per step.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "ceres/jet.h"
#include "engine/model/experiment.h"
#include "engine/model/rk4.h"

namespace vesselid {

inline double ScalarPart(double v) { return v; }
template <int N>
double ScalarPart(const ceres::Jet<double, N>& v) {
  return v.a;
}

// visitor(node, x, u_at_node) is called at every node, then the state is advanced.
// Returns false if the model rejects a state or the state stops being finite.
template <class Model, class T, class Visitor>
bool SimulateExperiment(const Model& model, const Experiment& e, const T* p, T* x,
                        Visitor&& visitor) {
  constexpr int n = Model::kNumStates;
  const int nu = e.num_inputs;
  const double* u = e.input_cache.data();
  const int nodes = e.num_nodes();
  for (int k = 0; k < nodes; ++k) {
    for (int i = 0; i < n; ++i) {
      if (!std::isfinite(ScalarPart(x[i]))) return false;
    }
    visitor(k, x, u);
    if (k + 1 == nodes) break;
    const int steps = e.node_substeps[k];
    const double h = e.node_step[k];
    for (int s = 0; s < steps; ++s, u += 3 * nu) {
      if (!Rk4Step(model, u, u + nu, u + 2 * nu, p, h, x)) return false;
    }
  }
  return true;
}

// The same with the experiment's input corrections (input_noise.h) added to the cached latent
// inputs: u = cache + c[offset + step_interval[step]] for each corrected input, formed per
// step in a fixed-size array (the corrections' index per step is precomputed).
template <class Model, class T, class Visitor>
bool SimulateExperimentCorrected(const Model& model, const Experiment& e, const T* corrections,
                                 const T* p, T* x, Visitor&& visitor) {
  constexpr int n = Model::kNumStates;
  constexpr int nu = Model::kNumInputs;
  const double* u = e.input_cache.data();
  std::array<T, 3 * nu> v;
  const int total_steps = static_cast<int>(e.input_corrections.front().step_interval.size());
  // Rows [0, rows) of the cache at u, corrected as step `step`.
  auto load = [&](int rows, int step) {
    for (int r = 0; r < rows * nu; ++r) v[r] = T(u[r]);
    for (const InputCorrectionGrid& g : e.input_corrections) {
      const T& c = corrections[g.offset + g.step_interval[step]];
      for (int r = 0; r < rows; ++r) v[r * nu + g.input] += c;
    }
  };
  const int nodes = e.num_nodes();
  int step = 0;
  for (int k = 0; k < nodes; ++k) {
    for (int i = 0; i < n; ++i) {
      if (!std::isfinite(ScalarPart(x[i]))) return false;
    }
    load(1, std::min(step, total_steps - 1));
    visitor(k, x, v.data());
    if (k + 1 == nodes) break;
    const int steps = e.node_substeps[k];
    const double h = e.node_step[k];
    for (int s = 0; s < steps; ++s, u += 3 * nu, ++step) {
      load(3, step);
      if (!Rk4Step(model, v.data(), v.data() + nu, v.data() + 2 * nu, p, h, x)) return false;
    }
  }
  return true;
}

}  // namespace vesselid

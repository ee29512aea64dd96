// Simulation of one prepared experiment: RK4 from node to node over the whole record,
// handing the state at every node to a visitor (which forms outputs and residuals).
// This is the hot path: no allocation, no virtual call, no lookup per step.
#pragma once

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

}  // namespace vesselid

// Inputs and states of the Erunsal 6-DOF model for tests: restrictions to DOF sets, commands
// sweeping both thrusters (wind optional), and a small initial state in every DOF.
#pragma once

#include <cmath>
#include <initializer_list>
#include <vector>

#include "engine/data/trajectory.h"
#include "problems/erunsal6dof/erunsal_model.h"

namespace vesselid::testing {

inline erunsal6dof::Model Restricted(const std::vector<int>& dofs) {
  erunsal6dof::Model model;
  model.active.fill(false);
  for (int d : dofs) model.active[d] = true;
  return model;
}

// c_L, c_R sweeping sinusoidally (and a steady wind when asked) every dt for `duration`.
inline Trajectory ErunsalCommands(double duration, double dt, bool wind) {
  Trajectory t;
  t.names = {"c_L", "c_R"};
  if (wind) t.names.insert(t.names.end(), {"wind_speed", "wind_direction"});
  t.columns.resize(t.names.size());
  for (int k = 0; k * dt <= duration + 1e-9; ++k) {
    const double s = k * dt;
    t.t.push_back(s);
    t.columns[0].push_back(0.5 + 0.4 * std::sin(0.7 * s));
    t.columns[1].push_back(0.5 + 0.4 * std::sin(0.45 * s + 1.0));
    if (wind) {
      t.columns[2].push_back(3.0);
      t.columns[3].push_back(0.8);
    }
  }
  return t;
}

// [x y z phi theta psi u v w p q r], the inactive DOFs of `model` at rest.
inline std::vector<double> ErunsalInitialState(const erunsal6dof::Model& model) {
  std::vector<double> x0 = {0.0, 0.0, 0.01, 0.15, 0.05, 0.2, 0.3, 0.05, 0.0, 0.1, 0.0, 0.05};
  for (int d = 0; d < 6; ++d) {
    if (!model.active[d]) x0[d] = x0[6 + d] = 0.0;
  }
  return x0;
}

}  // namespace vesselid::testing

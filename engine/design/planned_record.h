// A planned experiment as the vessel would log it: every input and the outputs the current
// model predicts, every sample_time s from t = 0. The inputs come from a command (a function
// of the time and, for closed-loop manoeuvres such as a zigzag, of the outputs) through the
// actuators: the command clipped to [lower, upper] and followed at no more than `rate`,
//   u_{k+1} = u_k + clamp(clip(c_k) - u_k, -rate dt, rate dt),
// so every planned input meets its limits by construction. Between samples the inputs are
// linear and the model is advanced by RK4 steps of at most max_step (the run's integration
// step; 0: one per sample), as an identification of the log would simulate it.
#pragma once

#include <functional>
#include <vector>

#include "Eigen/Core"
#include "engine/model/model_handle.h"

namespace vesselid {

struct PlannedRecord {
  std::vector<double> time;  // s
  Eigen::MatrixXd inputs;    // samples x model inputs, model units
  Eigen::MatrixXd outputs;   // samples x model outputs, predicted
  bool finite = false;       // the simulation reached the end with finite states
};

// The command of every input at time t from the outputs y at t (model units).
using InputCommand = std::function<void(double t, const double* y, double* command)>;

struct Actuators {
  std::vector<double> lower, upper, rate;  // per model input; rate 0: no limit
  std::vector<double> start;               // per model input, the value at t = 0
};

// Simulates the plan from x0 with parameters p for `duration` s. `stop` (may be empty) ends it
// early once true (a zigzag's last reversal). False when the model refuses a state or it
// stops being finite (record->finite false; the samples reached are kept).
bool RealizePlan(const ModelHandle& model, const std::vector<double>& p,
                 const std::vector<double>& x0, double duration, double sample_time,
                 double max_step, const Actuators& actuators, const InputCommand& command,
                 PlannedRecord* record, const std::function<bool()>& stop = {});

// The state after `duration` s from *x at constant inputs u (RK4 steps of at most max_step),
// in *x; false when the model refuses a state or it stops being finite.
bool SettleState(const ModelHandle& model, const std::vector<double>& p, double duration,
                 double max_step, const std::vector<double>& u, std::vector<double>* x);

}  // namespace vesselid

// The process noise a filter-error stage identified with the ship (`noise: {process: ...}`,
// docs/models.md "Disturbance models"): white noise of spectral density q on the state
// equation of `state`,
//
//   dx_i = f_i(x, u, theta) dt + sqrt(q_i) dW_i,
//
// the gusts and waves that push the ship. It is what a trial in the sea the model was
// identified in adds to the ship's own motion (`vesselid predict`'s interval "with the
// disturbance"); the sensors' noise (white, AR(1), wave yaw in the heading, a drifting bias)
// does not move the ship and is not here.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "engine/run/run_result.h"

namespace vesselid {

struct ProcessNoise {
  std::string state;                                           // the model's state
  double spectral_density = std::numeric_limits<double>::quiet_NaN();  // q, (state unit)^2/s
  double std_error = std::numeric_limits<double>::quiet_NaN();         // NaN where none
};

// The process noise among a stage's estimates: those of kind noise named "q.process.<state>".
std::vector<ProcessNoise> ProcessNoiseOf(const std::vector<Estimate>& estimates);

// The same from one estimate's name and values as results.json lists them; false where the
// name is no process noise's.
bool ProcessNoiseNamed(const std::string& name, double value, double std_error,
                       ProcessNoise* noise);

}  // namespace vesselid

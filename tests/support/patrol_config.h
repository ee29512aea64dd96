// Seed 003's patrol vessel as the head of a test config: the second-order Nomoto model, its
// closed-loop single-sine simulation of `duration` seconds and the experiment on it. Tests
// append their stages (and studies).
#pragma once

#include <string>

namespace vesselid::testing {

inline std::string PatrolConfigHead(int duration) {
  return R"(
model: {family: nomoto, type: second_order}
simulation:
  truth: {T1: 2.0875, T2: 0.3179, T3: 0.1830, K: -0.1724}
  steering_gear: {Tm: 1.0, kp: 0.7, rudder_limit_deg: 35}
  sample_time: 0.02
  experiments:
    - {file: patrol.csv, duration: )" +
         std::to_string(duration) + R"(, excitation: {type: sine, amplitude_deg: 20, period: 30}}
experiments:
  - {name: sine, file: patrol.csv, inputs: {delta: delta}, outputs: {psi: psi},
     interpolation: {delta: cubic}}
)";
}

}  // namespace vesselid::testing

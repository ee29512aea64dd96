// Synthetic steering experiments as seed 003 Table 3 sets them up: a Nomoto vessel, a
// first-order steering gear delta' = (delta_set - delta) / Tm, rudder limited to
// +-rudder_limit, sampled every sample_time from a zero initial state. The command is
//   heading control:  delta_set = sign(K) kp (psi_set(t) - psi)   (stable for K < 0 too)
//   zigzag:           delta_set = +-zigzag_rudder, switched when psi passes +-zigzag_heading;
//   planned:          delta_set(t) from a table (a plan of `vesselid design`), linear between
//                     its samples and held after the last.
// psi_set is a single sine (seed) or a Schroeder-phased multi-sine. Gaussian noise is added
// to the recorded rudder angle and heading.
//
// What a real log has and the identified model does not: a steering gear rate limit
// (|delta'| <= rudder_rate); a rudder bias (the ship steers on delta + rudder_bias, the log
// records delta: a per-run delta_0 to the model); a slow yaw disturbance (wind, current,
// bank effect) as an equivalent rudder angle disturbance_amplitude sin(2 pi t / period + phi),
// phi drawn from the seed; a heading sensor of finite resolution; a speed input U held at
// `speed` for models that take one (n1-forms with a length).
#pragma once

#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/model/model_handle.h"

namespace vesselid::nomoto {

struct Excitation {
  enum class Type { kSine, kMultisine, kZigzag, kPlanned };
  Type type = Type::kSine;
  double amplitude = 0.0;  // psi_set amplitude [rad] (multi-sine: peak of the sum's rms x sqrt2)
  std::vector<double> periods;  // one period for sine, several for multi-sine [s]
  double zigzag_rudder = 0.0;   // [rad]
  double zigzag_heading = 0.0;  // [rad]
  double zigzag_first = 1.0;    // +1: the first rudder turns the ship to starboard, -1: port
  std::vector<double> planned_t, planned_delta;  // planned: the command's samples [s], [rad]
};

struct ClosedLoopOptions {
  double steering_time_constant = 1.0;  // Tm [s]
  double controller_gain = 1.0;         // kp
  double rudder_limit = 35.0 * M_PI / 180.0;
  double sample_time = 0.02;
  int substeps = 4;  // RK4 steps per sample
  double duration = 100.0;
  Excitation excitation;
  double rudder_noise = 0.0;   // std [rad]
  double heading_noise = 0.0;  // std [rad]
  double heading_resolution = 0.0;     // > 0: the logged heading is rounded to it [rad]
  double rudder_rate = 0.0;            // > 0: steering gear rate limit [rad/s]
  double rudder_bias = 0.0;            // [rad], not in the logged rudder angle
  double disturbance_amplitude = 0.0;  // [rad] of rudder
  double disturbance_period = 0.0;     // [s]
  double speed = 0.0;                  // U [m/s] for a model with a speed input
  unsigned seed = 1;

  bool IsValid(std::string* error) const;
};

// Simulates the closed loop with any Nomoto-family model (input delta and optionally U,
// outputs psi and r). The sign of the rudder's effect comes from K, K_nd or b.
// Columns: psi_set, delta_set, delta (noisy), psi (noisy), r (true), delta_true, psi_true,
// and U when the model takes a speed.
bool SimulateClosedLoop(const ModelHandle& model, const std::vector<double>& parameters,
                        const ClosedLoopOptions& options, Trajectory* trajectory,
                        std::string* error);

}  // namespace vesselid::nomoto

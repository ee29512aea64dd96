// Synthetic steering experiments as seed 003 Table 3 sets them up: a Nomoto vessel, a
// first-order steering gear delta' = (delta_set - delta) / Tm, rudder limited to
// +-rudder_limit, sampled every sample_time from a zero initial state. The command is
//   heading control:  delta_set = sign(K) kp (psi_set(t) - psi)   (stable for K < 0 too)
//   zigzag:           delta_set = +-zigzag_rudder, switched when psi passes +-zigzag_heading.
// psi_set is a single sine (seed) or a Schroeder-phased multi-sine. Gaussian noise is added
// to the recorded rudder angle and heading.
#pragma once

#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/model/model_handle.h"

namespace vesselid::nomoto {

struct Excitation {
  enum class Type { kSine, kMultisine, kZigzag };
  Type type = Type::kSine;
  double amplitude = 0.0;  // psi_set amplitude [rad] (multi-sine: peak of the sum's rms x sqrt2)
  std::vector<double> periods;  // one period for sine, several for multi-sine [s]
  double zigzag_rudder = 0.0;   // [rad]
  double zigzag_heading = 0.0;  // [rad]
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
  unsigned seed = 1;

  bool IsValid(std::string* error) const;
};

// Simulates the closed loop with any Nomoto-family model (input delta, outputs psi and r).
// Columns: psi_set, delta_set, delta (noisy), psi (noisy), r (true), delta_true, psi_true.
bool SimulateClosedLoop(const ModelHandle& model, const std::vector<double>& parameters,
                        const ClosedLoopOptions& options, Trajectory* trajectory,
                        std::string* error);

}  // namespace vesselid::nomoto

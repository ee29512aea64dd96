// A KVLCC2-like free-running campaign at model scale (`vesselid simulate` with an mmg config):
// zigzags and turning circles of the MMG model (mmg_model.h) with the published coefficients
// or a config's truth, as a tank's tracking system logs them.
//
// Each run starts on a straight course at the self-propulsion speed of its propeller rate
// (X = 0 at v = r = 0, bisection on u), heading 0, at the origin. The rudder command is
//   zigzag:  +-rudder (the first side from `first`), reversed when the heading change passes
//            +-heading;
//   turning: +-rudder held from t = 0;
// and the steering gear follows it as delta' = (delta_set - delta)/Tm, limited to the rate
// limit. What the log has and the identified model does not: that rate limit's effect is
// logged (delta is the measured angle), but a rudder bias (the ship steers on
// delta + rudder_bias, the log records delta) and a slow disturbance (wind, current, the
// tank's return flow) as an equivalent rudder angle amplitude sin(2 pi t/period + phase), the
// phase drawn from the seed, are not; Gaussian noise on positions, heading, speed and rudder.
// Columns: x, y, psi, U, delta, n (logged), u_true, v_true, r_true, delta_true, psi_true.
#pragma once

#include <string>

#include "engine/data/trajectory.h"
#include "engine/model/model_handle.h"

namespace vesselid::mmg {

struct CampaignRun {
  enum class Type { kZigzag, kTurning };
  Type type = Type::kZigzag;
  double rudder = 0.0;           // rad
  double heading = 0.0;          // rad, the zigzag's switching heading change
  double first = 1.0;            // +1: starboard first (or a starboard turn), -1: port
  double duration = 60.0;        // s
  double propeller_rate = 10.4;  // n [1/s]
  double rudder_bias = 0.0;      // rad, not in the logged rudder angle
  double disturbance_amplitude = 0.0, disturbance_period = 0.0;  // rad of rudder, s
  double position_noise = 0.0, heading_noise = 0.0, speed_noise = 0.0, rudder_noise = 0.0;
  double sample_time = 0.1;
  int substeps = 4;
  double steering_time_constant = 0.1;                         // Tm [s]
  double rudder_rate = 15.8 * 3.14159265358979323846 / 180.0;  // rad/s; 0: no limit
  unsigned seed = 1;

  bool IsValid(std::string* error) const;
};

// The straight-course speed at propeller rate n: u with X(u, v = 0, r = 0, delta = 0) = 0.
// False when no u in (0, 20] m/s balances the forces.
bool SelfPropulsionSpeed(const ModelHandle& model, const double* parameters, double n,
                         double* speed);

// Simulates one run of the MMG model (states x, y, psi, u, v, r; inputs delta, n).
bool SimulateRun(const ModelHandle& model, const std::vector<double>& parameters,
                 const CampaignRun& run, Trajectory* trajectory, std::string* error);

}  // namespace vesselid::mmg

// Synthetic free-running campaign like seed 000's (Yellowfish ASV): one continuous voyage of
// the physical catamaran, cut into logged segments separated by unlogged transitions during
// which the commands ramp linearly to the next segment's first command.
//
// The operator drives joystick mean u_m and difference u_d; the propellers get
//   u_L = clamp(u_m + u_d, -1, 1),   u_R = clamp(u_m - u_d, -1, 1),
// sampled every pwm_period and held. Since u_m > 0 always, both never run in reverse.
// Segment types, in shuffled order with fixed shares (forward 35 %, zigzag 15 %, circles
// 50 %), 12-40 s each, durations summing to total_duration:
//   forward, constant speed:  u_m in [0.3, 0.9], slowly wandering |u_d| <= 0.04
//   forward, varying speed:   u_m stepped and ramped within [0.2, 1.0], wandering u_d
//   zigzag:                   u_m in [0.4, 0.8], u_d = +-[0.15, 0.3] switched when the heading
//                             passes +-[15, 25] deg about the segment's initial heading
//   circle, constant rate:    u_m in [0.15, 0.5], |u_d| in [0.25, 0.55], either sign
//   circle, varying rate:     u_d ramped within +-[0.3, 0.55] (reversing the turn one time in
//                             four) or oscillating about +-[0.3, 0.4]; u_m constant or ramped
//                             in [0.15, 0.6]
// Circle means favour low values, so that one propeller runs in reverse on ~35-40 % of the
// PWM samples.
//
// Logged at three unsynchronised rates, NaN where a sensor has no sample:
//   t, segment, n, e (GNSS, noisy), heading (AHRS, noisy, wrapped to (-pi, pi]),
//   pwm_L, pwm_R (exactly what the propellers get), u_true, v_true, r_true (AHRS rows).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "problems/input_gain/catamaran.h"
#include "problems/input_gain/quadratic_usv.h"

namespace vesselid::input_gain {

// Real-log defects put into a campaign (segment indices; -1: none): a segment whose
// transition is skipped, so that its first seconds are a manoeuvre starting, and a segment
// with one GNSS fix thrown off by `glitch_offset` m north (half of it west).
struct LogDefects {
  int abrupt_start_segment = -1;
  int glitch_segment = -1;
  double glitch_offset = 12.0;
};

struct CampaignOptions {
  int segments = 127;
  double total_duration = 53.42 * 60.0;  // s, logged time summed over all segments
  double min_segment = 12.0;             // s, bounds of one segment's duration
  double max_segment = 40.0;
  double gap = 3.0;           // s, unlogged transition before every segment (and before the first)
  double gnss_period = 0.2;   // s (5 Hz)
  double gnss_offset = 0.03;  // s, sample times gnss_offset + k gnss_period
  double ahrs_period = 0.02;  // s (50 Hz), sample times k ahrs_period
  double pwm_period = 0.1;    // s (10 Hz), command update and log
  double pwm_offset = 0.01;   // s, sample times pwm_offset + k pwm_period
  double gnss_noise = 0.02;   // m, standard deviation per axis (RTK)
  double heading_noise = 0.3 * M_PI / 180.0;  // rad, standard deviation
  unsigned seed = 1;    // operator plan; the noise uses an independent stream of the same seed
  double step = 0.005;  // s, RK4 step; periods and offsets must be multiples of it
  bool truth_columns = true;  // add noiseless u_true, v_true, r_true on AHRS rows
  LogDefects defects;
  // Every PWM clamped to [0, 1]: a campaign run without astern thrust.
  bool forward_only = false;
  // A planned experiment (`vesselid design`'s planned_input.csv) instead of the campaign: one
  // segment (id 0) whose PWMs follow the plan (linear between its samples, sampled every
  // pwm_period), after `lead_in` s from rest on the plan's first command, unlogged.
  std::vector<double> planned_t, planned_left, planned_right;
  double lead_in = 30.0;

  bool IsValid(std::string* error) const;
};

// Simulates the whole campaign from rest at the origin, heading north, with seed 000's
// catamaran or with the quadratic-thrust USV (quadratic_usv.h: a structure the identified
// model does not have).
bool SimulateCampaign(const CatamaranParameters& parameters, const CampaignOptions& options,
                      Trajectory* out, std::string* error);
bool SimulateCampaign(const QuadraticUsvParameters& parameters, const CampaignOptions& options,
                      Trajectory* out, std::string* error);

}  // namespace vesselid::input_gain

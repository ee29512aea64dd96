// Synthetic experiments with the physical planing craft (craft.h) for the eriksen2dof model:
// seed 004's step campaign (§3.2) for identification, and separate validation runs.
//
// Step campaign: for every rudder setting one run with the throttle stepped 0 -> 1 -> 0 in
// steps of throttle_step (0, 0.1, ..., 1, 0.9, ..., 0: 21 levels by default), then for every
// throttle setting one run with the rudder stepped 0 -> 1 -> 0 in steps of rudder_step. Each
// level is held until settled, then for one full turn, 2 pi / |r|, clamped to
// [min_steady, max_steady], so that averaging removes the current and wind. "Settled" is
// judged, as an operator watching the instruments would, on the noise-free response of a
// shadow craft driven by the same commands in still water and calm air (the real one keeps
// oscillating with the turn through wind and current): the level's settling phase ends once
// it has lasted min_settle and the shadow's |u'| and |r'| have stayed below
// settle_acceleration and settle_yaw_acceleration for settle_window (at most max_settle).
//
// Validation runs, validation_duration each, kind i % 4 for run i:
//   0  random simultaneous steps, holds 10-40 s, tau_m in the validation throttle range,
//      tau_delta in [-1, 1];
//   1  smooth: throttle a triangle wave (ramps) over the range, period 120-240 s; rudder
//      a sum of two sinusoids (periods 60-120 s and 12-30 s) within [-1, 1];
//   2  negative rudder: throttle steps every 20-60 s, rudder steps in [-1, 0] every 15-45 s;
//   3  tracking-like, no steady states: both inputs piecewise linear through random knots
//      4-12 s apart.
//
// Every run starts from its first command's steady state (still-water steady state, then an
// unlogged warm_up in the real environment) at n = e = 0. Runs follow each other in time with
// run_gap s between them (t strictly increasing over the file). Commands change only at
// samples and are held over the sample period (zero-order hold).
//
// Environment: uniform current; wind of mean speed wind_speed plus a gust speed g following
// the first-order Gauss-Markov process g' = -g / T_g + sqrt(2 / T_g) gust_sd w (exactly
// discretised per integration step), wind speed floored at 0.
//
// Columns (after t): run (0, 1, ... per run, rows of one run contiguous), n, e (m, noisy),
// course (course over ground, rad, noisy, wrapped to (-pi, pi]), sog (m/s, noisy), rot (yaw
// rate, rad/s, noisy), throttle, rudder (the commands exactly), sog_true, rot_true (noise-free).
// Noise is white Gaussian per sample; everything is a function of `seed` only.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "problems/eriksen2dof/craft.h"

namespace vesselid::eriksen2dof {

struct CampaignOptions {
  // Step campaign.
  std::vector<double> rudder_settings = {0.0, 0.2, 0.4, 0.6, 0.8, 1.0};    // of throttle runs
  std::vector<double> throttle_settings = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6};  // of rudder runs
  double throttle_step = 0.1;          // tau_m increment; 1 / throttle_step must be an integer
  double rudder_step = 0.1;            // tau_delta increment; 1 / rudder_step must be an integer
  double min_settle = 10.0;            // s, shortest settling phase of a level
  double max_settle = 300.0;           // s, longest settling phase (ends even if not settled)
  double settle_window = 5.0;          // s, how long the shadow must stay quiet
  double settle_acceleration = 0.005;  // m/s^2, quiet: |u'| below this
  double settle_yaw_acceleration = 0.0005;  // rad/s^2, quiet: |r'| below this
  double min_steady = 20.0;                 // s, shortest hold after settling
  double max_steady = 150.0;                // s, longest hold after settling (r ~ 0: no full turn)

  // Validation runs.
  int validation_runs = 4;
  double validation_duration = 540.0;    // s, per run
  double validation_throttle_min = 0.0;  // tau_m range of the validation runs
  double validation_throttle_max = 0.6;

  // Environment.
  double current_speed = 0.3;                    // m/s
  double current_direction = 60.0 * M_PI / 180;  // rad, direction it flows towards (from N)
  double wind_speed = 6.0;                       // m/s, mean
  double wind_direction = 225.0 * M_PI / 180;    // rad, direction it blows from (from N)
  double gust_sd = 1.0;                          // m/s, stationary SD of the gust speed
  double gust_time_constant = 8.0;               // s, T_g

  // Timing and sensors.
  double sample_period = 0.2;   // s, log and command period; a multiple of step
  double step = 0.02;           // s, RK4 step
  double warm_up = 60.0;        // s, unlogged run-in before each run
  double run_gap = 5.0;         // s, time between the last sample of a run and the next run
  double position_noise = 0.5;  // m, SD per axis
  double course_noise = 0.5 * M_PI / 180;  // rad, SD
  double sog_noise = 0.05;                 // m/s, SD
  double rot_noise = 0.2 * M_PI / 180;     // rad/s, SD
  unsigned seed = 1;  // commands, gusts and noise use independent streams of this seed

  bool IsValid(std::string* error) const;
};

// The step campaign (identification data).
bool SimulateStepCampaign(const CraftParameters& parameters, const CampaignOptions& options,
                          Trajectory* out, std::string* error);

// The validation runs (other input sequences, same environment, independent random streams).
bool SimulateValidationRuns(const CraftParameters& parameters, const CampaignOptions& options,
                            Trajectory* out, std::string* error);

}  // namespace vesselid::eriksen2dof

// A twin-thruster field log as a small USV's logger writes it, made from a simulated campaign
// (campaign.h) sampled every RK4 step: what a real recording brings that a simulation does
// not.
//
//   * one row per logger tick, nominal rate `rate`, each row's time off its tick by a uniform
//     +-`jitter` (quantised to the campaign's sample step);
//   * PWM and heading on every row, heading in degrees on [0, 360) as a compass gives it;
//   * GNSS fixes on every other row as WGS84 latitude and longitude (degrees): the campaign's
//     local north/east (m) taken as the ellipsoid's local tangent plane at `origin`
//     (ENU -> ECEF -> geodetic, exact to well under a millimetre);
//   * defects: one fix lat = lon = 0 (`zero_fix_segment`), the GNSS repeating its last fix
//     `stale_fixes` times (`stale_segment`), and one segment cut to `short_s` seconds
//     (`short_segment`); -1: none.
//
// Columns: t, segment, lat, lon, heading, pwm_L, pwm_R (empty where not sampled).
#pragma once

#include <string>

#include "engine/data/trajectory.h"

namespace vesselid::input_gain {

struct FieldLogOptions {
  double origin_lat = 63.44;  // deg, where the campaign's n = e = 0 lies
  double origin_lon = 10.40;  // deg
  double rate = 10.0;         // Hz, logger rows
  double jitter = 0.03;       // s, +- about each tick
  int zero_fix_segment = -1;
  int stale_segment = -1;
  int stale_fixes = 4;  // repeats of the last fix
  int short_segment = -1;
  double short_s = 2.0;  // s

  bool IsValid(std::string* error) const;
};

// The campaign's sample step (s) its columns n, e, heading must be sampled at for a log.
inline constexpr double kFieldLogCampaignStep = 0.005;

// `campaign`: columns segment, n, e, heading (rad), pwm_L, pwm_R with n, e, heading on every
// row, kFieldLogCampaignStep apart within a segment. `seed` draws the jitter.
bool MakeFieldLog(const Trajectory& campaign, const FieldLogOptions& options, unsigned seed,
                  Trajectory* log, std::string* error);

// The geodetic latitude and longitude (deg) of local north/east (m) on the WGS84 tangent plane
// at (lat0, lon0) (height 0 there).
void LocalToGeodetic(double lat0, double lon0, double north, double east, double* lat, double* lon);

}  // namespace vesselid::input_gain

// Turning circle figures as IMO MSC.137(76) defines them, from a track (x north, y east),
// the heading psi(t) and the rudder delta(t) that flew it.
//
// A turning circle test puts the rudder hard over from a straight course and holds it. With
// t_0 the rudder execute, p_0 and psi_0 the position and heading there, e_0 = (cos psi_0,
// sin psi_0) the original course and n_0 = (-sin psi_0, cos psi_0) its normal, s the sign of
// the heading change and t_90, t_180 the times the heading change s (psi - psi_0) reaches
// 90 and 180 deg (linear between samples):
//   advance              (p(t_90) - p_0) . e_0       (along the original course)
//   transfer             |(p(t_90) - p_0) . n_0|     (across it)
//   tactical diameter    |(p(t_180) - p_0) . n_0|
//   times to 90 and 180 deg of heading change        t_90 - t_0, t_180 - t_0
// A figure is unknown where the record ends before its heading change.
//
// A record is a turning circle when its rudder moves away from its first value delta_a by a
// largest amount delta_t >= 5 deg (t_0: the first sample 10 % of the way), then, once within
// 90 % of delta_t, stays on that side above half of it for the rest of the record, and the
// heading turns at least 90 deg.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace vesselid {

struct TurningTest {
  double rudder = 0.0;   // delta_t - delta_a, signed [rad]
  double execute = 0.0;  // t_0
  double sign = 1.0;     // s: +1 when the heading increases (a starboard turn)
};

struct TurningFigures {
  static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  double advance = kUnknown;  // in the track's unit (m)
  double transfer = kUnknown;
  double tactical_diameter = kUnknown;
  double time_to_90 = kUnknown, time_to_180 = kUnknown;  // s
};

// Whether (t, delta, psi) is a turning circle (see above); NaN samples are skipped. `why`
// (may be null) says why not.
bool DetectTurningCircle(const std::vector<double>& t, const std::vector<double>& delta,
                         const std::vector<double>& psi, TurningTest* test,
                         std::string* why = nullptr);

// The figures of the track (x, y, psi; NaN samples skipped) for the test's t_0 and sign; p_0
// and psi_0 are the track's own at t_0 (the first sample at or after it).
TurningFigures MeasureTurningCircle(const std::vector<double>& t, const std::vector<double>& x,
                                    const std::vector<double>& y, const std::vector<double>& psi,
                                    const TurningTest& test);

}  // namespace vesselid

// Zigzag manoeuvre figures as IMO MSC.137(76) (and MSC/Circ.1053) define them, from a heading
// trace psi(t) and the rudder delta(t) that flew it.
//
// A zigzag test deflects the rudder to delta_z and reverses it each time the heading change
// from the base course psi_0 reaches +-psi_z (the "check"). With t_0 the first rudder execute,
// s the sign of the first heading change and Dpsi = s (psi - psi_0), psi_0 = psi(t_0):
//   executes   t_1 = first t > t_0 with Dpsi >= psi_z, t_2 = first t > t_1 with Dpsi <= -psi_z,
//              t_3 = first t > t_2 with Dpsi >= psi_z, ... (alternating)
//   first overshoot angle     max over [t_1, t_2] of  Dpsi - psi_z
//   second overshoot angle    max over [t_2, t_3] of -Dpsi - psi_z
//   time to the first check   t_1 - t_0 (the initial turning time)
//   period                    mean of t_{k+2} - t_k over the executes found (time between
//                             successive executes of the same sign, one full cycle)
// An overshoot is measured only where the heading turned back within the record (the next
// execute, or a maximum before the record's end).
//
// A record is a zigzag when its rudder switches between plateaus +-delta_z (|delta| above half
// its largest value, median of those; held there: 80 % of them above 0.8 delta_z, which a sine
// is not) at least twice after the first execute, and the heading
// changes at the reversals alternate in sign with magnitudes within 25 % of their median,
// psi_z; delta_z and psi_z are these medians.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace vesselid {

// rad/s: IMO's steering gear, 35 deg to 30 deg the other side in 28 s (MSC.137(76)).
inline constexpr double kImoRudderRate = 65.0 / 28.0 * 3.14159265358979323846 / 180.0;

// What DetectZigzag finds in a record (angles in radians).
struct ZigzagTest {
  double rudder = 0.0;         // delta_z
  double heading = 0.0;        // psi_z
  double first_execute = 0.0;  // t_0
  double sign = 1.0;           // s: +1 when the heading first increases
  int reversals = 0;           // rudder reversals after t_0
};

struct ZigzagFigures {
  static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  double first_overshoot = kUnknown;      // rad
  double second_overshoot = kUnknown;     // rad
  double time_to_first_check = kUnknown;  // s
  double period = kUnknown;               // s
  std::vector<double> executes;           // t_0, t_1, ...
};

// Whether (t, delta, psi) is a zigzag (see above); NaN samples are skipped. `why` (may be
// null) says why not.
bool DetectZigzag(const std::vector<double>& t, const std::vector<double>& delta,
                  const std::vector<double>& psi, ZigzagTest* test, std::string* why = nullptr);

// The figures of the heading trace `psi` (NaN samples skipped) for the test's t_0, psi_z and
// sign; psi_0 = psi at t_0 (the first sample at or after it).
ZigzagFigures MeasureZigzag(const std::vector<double>& t, const std::vector<double>& psi,
                            const ZigzagTest& test);

}  // namespace vesselid

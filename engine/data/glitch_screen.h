// A pre-screen of measured outputs for the defects of real logs, each removed sample set to
// NaN (a gap like any other):
//   * zero fixes: a position pair exactly 0/0 (a GNSS receiver without a solution);
//   * stale repeats: a channel repeating its value `stale` or more times in a row while
//     another screened channel changes (with one screened channel: a reference column, a
//     mapped input), a sensor that stopped updating: the repeats after the first are removed;
//   * jumps: a sample farther from the last kept one than a bound allows,
//       |y_k - y_last| > max_rate (t_k - t_last) + 7 sigma,
//     with sigma the channel's noise level (robust, from the median absolute second
//     difference) so that noise at a high sample rate is no jump; for the position pair the
//     distance is sqrt(dn^2 + de^2) and the rate max_speed. A lasting move (five
//     consecutive rejected samples consistent with each other) is the track, not a glitch:
//     the screen takes it back and starts again from there.
// Angle channels compare differences modulo their period (360 in degrees, 2 pi in radians).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/data/trajectory.h"

namespace vesselid {

struct GlitchScreenOptions {
  // The position pair in metres (empty: none), with its speed bound (m/s, 0: not checked).
  std::string north_column, east_column;
  double max_speed = 0.0;
  bool zero_fix = true;  // remove 0/0 positions of the pair
  // Other screened channels (measured outputs) with a rate bound in their unit per second
  // (0: none) and a period for angles (0: not an angle).
  struct Channel {
    std::string column;
    double max_rate = 0.0;
    double period = 0.0;
  };
  std::vector<Channel> channels;
  int stale = 0;  // a value repeated this many times in a row is stale (0: not checked)
  // Columns not screened whose change during a repeat marks it stale when only one channel
  // is screened (the mapped inputs: a heading held while the rudder moves, in a log with one
  // measured output).
  std::vector<std::string> reference_columns;
};

// What the screen removed: per kind and channel, the count and the first times.
struct GlitchFinding {
  GlitchFinding(std::string kind_, std::string channel_)
      : kind(std::move(kind_)), channel(std::move(channel_)) {}
  std::string kind;     // "zero fix", "stale repeat", "jump", "re-anchored"
  std::string channel;  // "north/east" or the column
  int count = 0;
  std::vector<double> first_times;  // at most kMaxTimes
  static constexpr size_t kMaxTimes = 3;
  void Add(double t) {
    ++count;
    if (first_times.size() < kMaxTimes) first_times.push_back(t);
  }
};

// Screens `data` in place; columns the options name must exist (the caller checks the
// mapping). The findings come in the order zero fixes, stale repeats, jumps.
std::vector<GlitchFinding> ScreenGlitches(const GlitchScreenOptions& options, Trajectory* data);

// "2 zero fixes of north/east (t = 12.3 s, 40 s), ..." for a note; empty when nothing.
std::string DescribeGlitches(const std::vector<GlitchFinding>& findings);

}  // namespace vesselid

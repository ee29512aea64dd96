// A record brought to a uniform time grid t_k = t_0 + k / rate (what equation-error
// regression and Savitzky-Golay differentiation assume), from logs whose rows jitter or whose
// channels come at different rates:
//   * measured outputs are interpolated linearly between their two neighbouring samples,
//     only where those are at most max_gap of the channel's median sample intervals apart
//     (a longer gap stays a gap: NaN), angles unwrapped by their period first;
//   * every other column (inputs, segment ids) holds its last sample (zero-order hold, a
//     command stays applied until the next one);
//   * a grid point in a gap of the log itself (no row for longer than max_gap median row
//     intervals: the logger was off, e.g. between segments) is empty in every column.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/data/trajectory.h"

namespace vesselid {

struct ResampleOptions {
  double rate = 0.0;     // Hz, > 0
  double max_gap = 3.0;  // median sample intervals an output may be interpolated across
  // Columns interpolated (the measured outputs), with their period if they are angles (0: not).
  std::map<std::string, double> interpolated;
};

struct ResampleReport {
  size_t rows_before = 0, rows_after = 0;
  int outside = 0;                        // grid points in gaps of the log, empty in every column
  std::map<std::string, int> left_empty;  // interpolated column: grid points in long gaps
};

// Replaces `data` by its values on the uniform grid; false (with a message naming the file)
// if the grid would exceed `max_rows` rows.
bool Resample(const ResampleOptions& options, std::uint64_t max_rows, Trajectory* data,
              ResampleReport* report, std::string* error);

}  // namespace vesselid

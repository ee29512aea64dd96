// A recorded experiment as read from CSV: a strictly increasing time column `t` and named
// channels; NaN marks a missing sample, so channels may have different rates and gaps.
#pragma once

#include <string>
#include <vector>

namespace vesselid {

struct Trajectory {
  std::string source;  // file it was read from, for messages
  std::vector<double> t;
  std::vector<std::string> names;            // channel names, header order (without t)
  std::vector<std::vector<double>> columns;  // columns[c][k], NaN where missing

  // Index of the channel called `name`, or -1.
  int Find(const std::string& name) const;
};

// The present samples of one channel: times and values with NaNs removed.
struct Channel {
  std::vector<double> t;
  std::vector<double> value;
};

Channel ExtractChannel(const Trajectory& trajectory, int column);

// Reads a CSV file: header row, a column `t` (seconds, strictly increasing), numeric fields,
// empty field = missing sample. Text that is not a number, NaN/inf, a wrong field count or a
// non-increasing time is rejected with "file:line: ..." in `error`.
bool ReadTrajectoryCsv(const std::string& path, Trajectory* trajectory, std::string* error);

// Writes columns to CSV (header `t,names...`; NaN written as an empty field), through a
// temporary file renamed at the end so that no reader sees a partial file.
bool WriteTrajectoryCsv(const std::string& path, const Trajectory& trajectory, std::string* error);

}  // namespace vesselid

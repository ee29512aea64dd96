// A recorded experiment as read from CSV: a strictly increasing time column `t` and named
// channels; NaN marks a missing sample, so channels may have different rates and gaps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/base/finding.h"

#include "engine/base/work_limits.h"

namespace vesselid {

struct Trajectory {
  std::string source;  // file it was read from, for messages
  std::vector<double> t;
  std::vector<int> line;  // the file line of each row, for messages (empty: not from a file)
  // An epoch log (time_base.h): t is relative to this Unix time, in nanoseconds.
  bool epoch = false;
  std::int64_t time_origin_ns = 0;
  // Local positions from GNSS fixes (gnss_position.h): their origin in degrees.
  bool position_origin = false;
  double origin_lat = 0.0, origin_lon = 0.0;
  // What preparing the data did to it (epoch origin, removed samples, resampling, skipped
  // pieces), one finding per concern naming the experiment: reported with the run's.
  std::vector<Finding> findings;
  // Cells of read columns that held text instead of a number (CsvReadOptions::max_bad_share),
  // one entry per such column; each cell is a missing sample (NaN) in `columns`.
  struct BadCells {
    std::string column;
    int count = 0;               // cells that are not numbers
    int cells = 0;               // rows of the file
    std::vector<double> times;   // the first few rows' times
    std::vector<int> lines;      // and their file lines
    std::string first_text;      // the first such cell as written
  };
  std::vector<BadCells> bad_cells;
  // Header names of the columns skipped unread (CsvReadOptions::columns), "" for an unnamed one.
  std::vector<std::string> skipped_columns;
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

// No measurement of a vessel is this large in any unit, and the square of a residual of this
// size overflows a cost summed over millions of samples: such a field is refused.
constexpr double kMaxDataMagnitude = 1e100;

// An experiment's default CsvReadOptions::max_bad_share (its `bad_cells` key).
constexpr double kDefaultBadCellShare = 0.05;

struct CsvReadOptions {
  char separator = ',';  // ',', ';' or '\t'
  std::string time_column = "t";
  std::uint64_t max_bytes = WorkLimits().file_bytes;
  std::uint64_t max_values = WorkLimits().data_values;  // rows x columns
  // Columns read besides the time column (empty: every column). The others, and columns
  // without a name, are skipped unread, so text in them (a timestamp string, a spreadsheet's
  // index column) is no error.
  std::vector<std::string> columns;
  // Share of a read column's cells that may hold text that is not a number (a mangled cell):
  // each becomes a missing sample, listed in Trajectory::bad_cells. 0: the first refuses the
  // file; above the share the file is refused naming the first such cell.
  double max_bad_share = 0.0;
  // Files of at least this many bytes are parsed in blocks on the machine's cores (the same
  // result; problems are still named by the sequential reader).
  std::uint64_t parallel_bytes = std::uint64_t{1} << 20;
};

// Reads a CSV file: header row, a time column (`t` unless named otherwise; seconds, strictly
// increasing; an epoch time is made relative to the first one without loss, time_base.h),
// numeric fields in the columns read (options.columns), empty field = missing sample; a UTF-8
// byte-order mark is skipped. A wrong field count, a time that is not a number or does not
// increase, a header split by another separator, a file past the limits, or more cells of a
// read column than max_bad_share that are not numbers (text, NaN/inf, a magnitude above
// kMaxDataMagnitude) is rejected with "file:line: ..." in `error`. Only a regular file is
// opened (input_file.h).
bool ReadTrajectoryCsv(const std::string& path, const CsvReadOptions& options,
                       Trajectory* trajectory, std::string* error);
inline bool ReadTrajectoryCsv(const std::string& path, Trajectory* trajectory, std::string* error) {
  return ReadTrajectoryCsv(path, CsvReadOptions(), trajectory, error);
}

// "';'" or "tabs", for messages.
std::string SeparatorName(char separator);

// Writes columns to CSV (header `t,names...`; NaN written as an empty field), through a
// temporary file renamed at the end so that no reader sees a partial file (and removed when
// the write fails).
bool WriteTrajectoryCsv(const std::string& path, const Trajectory& trajectory, std::string* error);

}  // namespace vesselid

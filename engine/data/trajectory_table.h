// A record handed over in memory (a program's arrays, a pandas DataFrame from Python) made
// into the Trajectory an experiment is built from, with the checks ReadTrajectoryCsv applies
// to the same numbers in a file, so that either source gives the same experiment.
#pragma once

#include <string>

#include "engine/data/trajectory.h"

namespace vesselid {

// `table` holds the record's columns by name (names/columns). Its time is either `table.t`
// (seconds, with table.epoch/time_origin_ns as the caller set them) or, when table.t is
// empty, the column named options.time_column. Of the other columns those in
// options.columns are kept (every named one when it is empty) and the rest listed in
// skipped_columns, as the CSV reader does. NaN is a missing sample.
//
// Refused with "<source>: ..." in `error` (source: table.source, else "data in memory"):
// no time column, fewer than two rows, columns of another length than the time, a time that
// is not finite or does not increase (naming the row), a duplicate column, more values than
// options.max_values, and a value that is infinite or beyond kMaxDataMagnitude (a missing
// sample is NaN). A first time of at least kEpochThreshold makes an epoch record: times
// relative to the first, its origin rounded to the nanosecond (a double holds an epoch time
// to about 0.2 us; integer nanoseconds, as from Python's datetime64, keep it exact).
bool TrajectoryFromTable(const Trajectory& table, const CsvReadOptions& options, Trajectory* out,
                         std::string* error);

}  // namespace vesselid

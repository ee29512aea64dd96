#include "engine/data/trajectory_table.h"

#include <cmath>
#include <cstdint>
#include <set>

#include "engine/base/format_numbers.h"
#include "engine/data/time_base.h"

namespace vesselid {

bool TrajectoryFromTable(const Trajectory& table, const CsvReadOptions& options, Trajectory* out,
                         std::string* error) {
  const std::string source = table.source.empty() ? "data in memory" : table.source;
  auto fail = [&](const std::string& what) {
    *error = source + ": " + what;
    return false;
  };
  if (table.names.size() != table.columns.size()) {
    return fail(std::to_string(table.names.size()) + " column names for " +
                std::to_string(table.columns.size()) + " columns");
  }
  Trajectory result;
  result.source = source;
  int time_column = -1;
  if (table.t.empty()) {
    for (size_t c = 0; c < table.names.size(); ++c) {
      if (table.names[c] == options.time_column) time_column = static_cast<int>(c);
    }
    if (time_column < 0) return fail("no time column '" + options.time_column + "'");
    result.t = table.columns[time_column];
  } else {
    result.t = table.t;
    result.epoch = table.epoch;
    result.time_origin_ns = table.time_origin_ns;
  }
  const size_t rows = result.t.size();
  if (rows < 2) return fail("fewer than two rows");
  const std::set<std::string> wanted(options.columns.begin(), options.columns.end());
  std::set<std::string> seen;
  std::vector<int> kept;
  for (size_t c = 0; c < table.names.size(); ++c) {
    if (static_cast<int>(c) == time_column) continue;
    const std::string& name = table.names[c];
    if (name.empty() || (!wanted.empty() && wanted.count(name) == 0)) {
      result.skipped_columns.push_back(name);
      continue;
    }
    if (!seen.insert(name).second) return fail("duplicate column '" + name + "'");
    if (table.columns[c].size() != rows) {
      return fail("column '" + name + "' has " + std::to_string(table.columns[c].size()) +
                  " rows, the time " + std::to_string(rows));
    }
    kept.push_back(static_cast<int>(c));
  }
  if (static_cast<double>(rows) * static_cast<double>(kept.size() + 1) >
      static_cast<double>(options.max_values)) {
    return fail(std::to_string(rows) + " rows x " + std::to_string(kept.size() + 1) +
                " columns is more than limits.data_values (" + std::to_string(options.max_values) +
                ")");
  }
  for (size_t k = 0; k < rows; ++k) {
    if (!std::isfinite(result.t[k])) {
      return fail("row " + std::to_string(k) + ": the time is not a finite number");
    }
    if (k > 0 && !(result.t[k] > result.t[k - 1])) {
      return fail("row " + std::to_string(k) + ": time " + FormatNumbers("%.17g", result.t[k]) +
                  " does not increase (previous " + FormatNumbers("%.17g", result.t[k - 1]) + ")");
    }
  }
  if (!result.epoch && std::abs(result.t.front()) >= kEpochThreshold) {
    const double t0 = result.t.front();
    result.epoch = true;
    result.time_origin_ns = static_cast<std::int64_t>(std::llround(t0 * 1e9));
    for (double& t : result.t) t -= t0;
  }
  for (int c : kept) {
    const std::vector<double>& values = table.columns[c];
    for (size_t k = 0; k < rows; ++k) {
      if (std::isnan(values[k]) || std::abs(values[k]) <= kMaxDataMagnitude) continue;
      return fail("column '" + table.names[c] + "', row " + std::to_string(k) + ": " +
                  FormatNumbers("%g", values[k]) +
                  " is not a measurement (a missing sample is NaN)");
    }
    result.names.push_back(table.names[c]);
    result.columns.push_back(values);
  }
  *out = std::move(result);
  return true;
}

}  // namespace vesselid

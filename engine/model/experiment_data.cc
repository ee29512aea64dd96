// LoadExperimentData: the preparation steps of experiment_data.h in order. Zero fixes go
// first (before an origin is chosen), the screen works in the columns' own units (its
// max_rate is in them), degrees become radians after it, and resampling comes last.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/base/format_numbers.h"
#include "engine/data/glitch_screen.h"
#include "engine/data/resample.h"
#include "engine/data/time_base.h"
#include "engine/data/trajectory_table.h"
#include "engine/model/experiment.h"

namespace vesselid {
namespace {

bool IsAngleOutput(const ExperimentSpec& spec, const std::string& output) {
  const std::vector<std::string>& angles = spec.data.angle_outputs;
  return std::find(angles.begin(), angles.end(), output) != angles.end();
}

// The position pair the screen's max_speed and zero fixes apply to: the channels `position`
// adds, else the columns of outputs x/y or n/e (the models' north and east).
bool PositionPair(const ExperimentSpec& spec, std::string* north, std::string* east) {
  if (spec.data.position) {
    *north = spec.data.gnss.north_column;
    *east = spec.data.gnss.east_column;
    return true;
  }
  for (const auto& [n, e] : {std::pair{"x", "y"}, std::pair{"n", "e"}}) {
    const auto a = spec.outputs.find(n), b = spec.outputs.find(e);
    if (a == spec.outputs.end() || b == spec.outputs.end()) continue;
    *north = a->second;
    *east = b->second;
    return true;
  }
  return false;
}

bool Screen(const ExperimentSpec& spec, const GnssPositionReport& gnss, Trajectory* data,
            std::string* error) {
  const ExperimentDataSpec& d = spec.data;
  std::vector<GlitchFinding> findings;
  if (!gnss.zero_fix_times.empty()) {
    GlitchFinding zero{"zero fix", d.gnss.lat_column + "/" + d.gnss.lon_column};
    for (double t : gnss.zero_fix_times) zero.Add(t);
    findings.push_back(zero);
  }
  if (d.screen) {
    GlitchScreenOptions options;
    std::string north, east;
    const bool pair = PositionPair(spec, &north, &east);
    if (!pair && (d.max_speed > 0.0 || d.zero_fix_given)) {
      *error = std::string(d.max_speed > 0.0 ? "screen.max_speed" : "screen.zero_fix") +
               " needs positions: a `position` map or outputs x, y (or n, e)";
      return false;
    }
    if (pair) {
      options.north_column = north;
      options.east_column = east;
      options.max_speed = d.max_speed;
      options.zero_fix = d.zero_fix && !d.position;  // `position` took them out already
    }
    options.stale = d.stale;
    for (const auto& [input, column] : spec.inputs) options.reference_columns.push_back(column);
    for (const auto& [output, column] : spec.outputs) {
      if (pair && (column == north || column == east)) continue;
      const auto rate = d.max_rate.find(output);
      double period = 0.0;
      if (IsAngleOutput(spec, output)) period = spec.IsDegreeColumn(column) ? 360.0 : 2.0 * M_PI;
      options.channels.push_back({column, rate == d.max_rate.end() ? 0.0 : rate->second, period});
    }
    std::vector<std::string> columns{options.north_column, options.east_column};
    for (const auto& c : options.channels) columns.push_back(c.column);
    for (const std::string& column : columns) {
      if (!column.empty() && data->Find(column) < 0) {
        *error = data->source + ": no column '" + column + "' (mapped as an output)";
        return false;
      }
    }
    const std::vector<GlitchFinding> more = ScreenGlitches(options, data);
    findings.insert(findings.end(), more.begin(), more.end());
  }
  if (findings.empty()) return true;
  Finding removed = MakeFinding(FindingKind::kSamplesRemoved,
                                "removed " + DescribeGlitches(findings) +
                                    (d.screen ? " (" + d.screen_key + ")" : ""));
  removed.experiment = spec.name;
  removed.count = 0;
  for (const GlitchFinding& g : findings) removed.count += g.count;
  removed.value = removed.count;
  data->findings.push_back(std::move(removed));
  return true;
}

bool ResampleRecord(const ExperimentSpec& spec, Trajectory* data, std::string* error) {
  ResampleOptions options;
  options.rate = spec.data.resample_rate;
  options.max_gap = spec.data.resample_max_gap;
  std::string outputs;
  for (const auto& [output, column] : spec.outputs) {
    if (options.interpolated.count(column) > 0) continue;
    options.interpolated[column] = IsAngleOutput(spec, output) ? 2.0 * M_PI : 0.0;
    outputs += (outputs.empty() ? "" : ", ") + column;
  }
  ResampleReport report;
  if (!Resample(options, spec.csv.max_values / std::max<size_t>(1, data->names.size() + 1), data,
                &report, error)) {
    return false;
  }
  char text[300];
  std::snprintf(text, sizeof(text),
                "': resampled to a uniform %g Hz grid (%zu rows from %zu; outputs %s "
                "interpolated linearly across gaps of up to %g samples, other columns held)",
                options.rate, report.rows_after, report.rows_before, outputs.c_str(),
                options.max_gap);
  std::string note = text + 3;  // after "': "
  if (report.outside > 0) {
    note += "; " + std::to_string(report.outside) +
            " grid point(s) in gaps of the log itself left empty";
  }
  for (const auto& [column, count] : report.left_empty) {
    note += "; " + std::to_string(count) + " grid point(s) of " + column +
            " left empty in its longer gaps";
  }
  Finding resampled = MakeFinding(FindingKind::kResampled, note);
  resampled.experiment = spec.name;
  resampled.value = options.rate;
  data->findings.push_back(std::move(resampled));
  return true;
}

// The columns an experiment reads: its inputs, outputs, degree columns, GNSS fixes and
// segment column. The others in the file are skipped unread.
std::vector<std::string> MappedColumns(const ExperimentSpec& spec) {
  std::vector<std::string> columns = spec.degree_columns;
  for (const auto& [input, column] : spec.inputs) columns.push_back(column);
  for (const auto& [output, column] : spec.outputs) columns.push_back(column);
  if (spec.data.position) {
    columns.push_back(spec.data.gnss.lat_column);
    columns.push_back(spec.data.gnss.lon_column);
  }
  if (!spec.segments.column.empty()) columns.push_back(spec.segments.column);
  return columns;
}

// One bad_cells finding per column whose mangled cells the reader turned into gaps.
void AddBadCellFindings(const ExperimentSpec& spec, Trajectory* data) {
  for (const Trajectory::BadCells& bad : data->bad_cells) {
    std::string where;
    for (size_t k = 0; k < bad.times.size(); ++k) {
      where += (k == 0 ? "" : ", ") + FormatNumbers("%g s", bad.times[k]) + " (line " +
               std::to_string(bad.lines[k]) + ")";
    }
    Finding f = MakeFinding(FindingKind::kBadCells,
                            "column '" + bad.column + "': " + std::to_string(bad.count) + " of " +
                                std::to_string(bad.cells) + " cells are not numbers (first '" +
                                bad.first_text + "'), read as missing samples; at t = " + where +
                                (bad.count > static_cast<int>(bad.times.size()) ? ", ..." : ""));
    f.experiment = spec.name;
    for (const auto* map : {&spec.inputs, &spec.outputs}) {
      for (const auto& [channel, column] : *map) {
        if (column == bad.column) f.output = channel;
      }
    }
    f.value = bad.count;
    f.count = 1;
    f.threshold = spec.csv.max_bad_share * bad.cells;
    data->findings.push_back(std::move(f));
  }
}

}  // namespace

std::string ReadKey(const ExperimentSpec& spec) {
  // Every field LoadExperimentData and the steps it calls read (but for names in messages):
  // a field added to them belongs here too.
  std::string key;
  const auto add = [&key](const std::string& text) {
    key += std::to_string(text.size()) + ':' + text + ';';  // length-prefixed: unambiguous
  };
  const auto number = [&add](double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.17g", value);
    add(text);
  };
  add(spec.file);
  add(spec.outside_data_folder);
  char table[32];
  std::snprintf(table, sizeof(table), "%p", static_cast<const void*>(spec.table.get()));
  add(table);
  add(std::string(1, spec.csv.separator));
  add(spec.csv.time_column);
  number(spec.data.time_scale);
  number(static_cast<double>(spec.csv.max_bytes));
  number(static_cast<double>(spec.csv.max_values));
  number(spec.csv.max_bad_share);
  number(static_cast<double>(spec.csv.parallel_bytes));
  for (const std::string& column : MappedColumns(spec)) add(column);
  add("|");
  for (const auto* map : {&spec.inputs, &spec.outputs}) {
    for (const auto& [channel, column] : *map) add(channel + '=' + column);
    add("|");
  }
  for (const std::string& column : spec.degree_columns) add(column);
  add("|");
  const ExperimentDataSpec& d = spec.data;
  add(d.position ? "position" : "");
  for (const std::string* text :
       {&d.gnss.lat_column, &d.gnss.lon_column, &d.gnss.north_column, &d.gnss.east_column}) {
    add(*text);
  }
  add(d.gnss.origin_first ? "first" : "given");
  number(d.gnss.origin_lat);
  number(d.gnss.origin_lon);
  add(d.screen ? "screen" : "");
  number(d.max_speed);
  for (const auto& [output, rate] : d.max_rate) {
    add(output);
    number(rate);
  }
  add("|");
  number(d.stale);
  add(d.zero_fix ? "zero_fix" : "");
  add(d.zero_fix_given ? "given" : "");
  number(d.resample_rate);
  number(d.resample_max_gap);
  for (const std::string& output : d.angle_outputs) add(output);
  return key;
}

bool LoadExperimentData(const ExperimentSpec& spec, Trajectory* trajectory, std::string* error) {
  CsvReadOptions csv = spec.csv;
  csv.columns = MappedColumns(spec);
  if (spec.table != nullptr) {
    if (!TrajectoryFromTable(*spec.table, csv, trajectory, error)) return false;
  } else if (!ReadTrajectoryCsv(spec.file, csv, trajectory, error)) {
    return false;
  }
  if (spec.data.time_scale != 1.0) {
    for (double& t : trajectory->t) t *= spec.data.time_scale;
  }
  AddBadCellFindings(spec, trajectory);
  if (!trajectory->skipped_columns.empty()) {
    std::string names;
    for (const std::string& name : trajectory->skipped_columns) {
      names += (names.empty() ? "" : ", ") + (name.empty() ? "(unnamed)" : "'" + name + "'");
    }
    Finding f = MakeFinding(FindingKind::kColumnsNotRead,
                            std::to_string(trajectory->skipped_columns.size()) +
                                " column(s) of the file not mapped, not read: " + names);
    f.experiment = spec.name;
    f.value = static_cast<double>(trajectory->skipped_columns.size());
    trajectory->findings.push_back(std::move(f));
  }
  auto fail = [&](const std::string& what) {
    *error = "experiment '" + spec.name + "': " + what;
    return false;
  };
  if (!spec.outside_data_folder.empty()) {
    Finding outside =
        MakeFinding(FindingKind::kOutsideDataFolder,
                    "read '" + spec.file + "', outside the data folder " +
                        spec.outside_data_folder + " (allowed by limits: {outside_data: true})");
    outside.experiment = spec.name;
    trajectory->findings.push_back(std::move(outside));
  }
  if (trajectory->epoch) {
    Finding origin = MakeFinding(FindingKind::kRecordOrigin,
                                 "times are Unix epoch seconds; t = 0 is " +
                                     FormatNanoseconds(trajectory->time_origin_ns) + " (" +
                                     FormatUtc(trajectory->time_origin_ns) +
                                     "), and windows, segments and reported times count from there");
    origin.experiment = spec.name;
    trajectory->findings.push_back(std::move(origin));
  }
  GnssPositionReport gnss;
  if (spec.data.position && !AddLocalPositions(spec.data.gnss, trajectory, &gnss, error)) {
    return fail(*error);
  }
  if (spec.data.position) {
    trajectory->position_origin = true;
    trajectory->origin_lat = gnss.origin_lat;
    trajectory->origin_lon = gnss.origin_lon;
  }
  if (!Screen(spec, gnss, trajectory, error)) return fail(*error);
  for (const std::string& column : spec.degree_columns) {
    int c = trajectory->Find(column);
    if (c < 0) {
      *error = trajectory->source + ": no column '" + column + "' (listed in experiment '" +
               spec.name + "' degrees)";
      return false;
    }
    for (double& v : trajectory->columns[c]) v *= M_PI / 180.0;
  }
  if (spec.data.resample_rate > 0.0 && !ResampleRecord(spec, trajectory, error)) {
    return fail(*error);
  }
  return true;
}

}  // namespace vesselid

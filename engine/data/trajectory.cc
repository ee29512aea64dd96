#include "engine/data/trajectory.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "engine/base/number_text.h"

namespace vesselid {
namespace {

std::string Trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  size_t e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    size_t comma = line.find(',', start);
    fields.push_back(Trim(line.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return fields;
}

}  // namespace

int Trajectory::Find(const std::string& name) const {
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  return -1;
}

Channel ExtractChannel(const Trajectory& trajectory, int column) {
  Channel channel;
  const std::vector<double>& values = trajectory.columns[column];
  for (size_t k = 0; k < values.size(); ++k) {
    if (std::isnan(values[k])) continue;
    channel.t.push_back(trajectory.t[k]);
    channel.value.push_back(values[k]);
  }
  return channel;
}

bool ReadTrajectoryCsv(const std::string& path, Trajectory* trajectory, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open file";
    return false;
  }
  Trajectory result;
  result.source = path;
  std::string line;
  int line_number = 0;
  int time_column = -1;
  std::vector<std::string> header;
  auto fail = [&](const std::string& what) {
    *error = path + ":" + std::to_string(line_number) + ": " + what;
    return false;
  };
  while (std::getline(in, line)) {
    ++line_number;
    if (Trim(line).empty()) continue;
    header = SplitFields(line);
    break;
  }
  if (header.empty()) return fail("empty file, expected a header row");
  std::set<std::string> seen;  // not a pairwise check: that is quadratic in a wide header
  for (size_t i = 0; i < header.size(); ++i) {
    if (header[i].empty())
      return fail("empty column name in header (column " + std::to_string(i + 1) + ")");
    if (!seen.insert(header[i]).second) return fail("duplicate column '" + header[i] + "'");
    if (header[i] == "t") {
      time_column = static_cast<int>(i);
    } else {
      result.names.push_back(header[i]);
    }
  }
  if (time_column < 0) return fail("header has no time column 't'");
  result.columns.resize(result.names.size());

  const double kMissing = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> fields;
  while (std::getline(in, line)) {
    ++line_number;
    if (Trim(line).empty()) continue;
    fields = SplitFields(line);
    if (fields.size() != header.size()) {
      return fail("expected " + std::to_string(header.size()) + " fields, found " +
                  std::to_string(fields.size()));
    }
    size_t channel = 0;
    for (size_t i = 0; i < fields.size(); ++i) {
      double value = kMissing;
      if (!fields[i].empty() && !ParseFiniteNumber(fields[i], &value)) {
        return fail("column '" + header[i] + "': '" + fields[i] + "' is not a finite number");
      }
      if (static_cast<int>(i) == time_column) {
        if (fields[i].empty()) return fail("missing time value");
        if (!result.t.empty() && !(value > result.t.back())) {
          return fail("time " + fields[i] + " is not after the previous time " +
                      std::to_string(result.t.back()) + " (t must be strictly increasing)");
        }
        result.t.push_back(value);
      } else {
        result.columns[channel++].push_back(value);
      }
    }
  }
  if (result.t.size() < 2) return fail("fewer than two data rows");
  *trajectory = std::move(result);
  return true;
}

bool WriteTrajectoryCsv(const std::string& path, const Trajectory& trajectory, std::string* error) {
  const std::string temporary = path + ".tmp";
  std::FILE* file = std::fopen(temporary.c_str(), "w");
  if (file == nullptr) {
    *error = path + ": cannot write file";
    return false;
  }
  std::fputs("t", file);
  for (const std::string& name : trajectory.names) std::fprintf(file, ",%s", name.c_str());
  std::fputc('\n', file);
  for (size_t k = 0; k < trajectory.t.size(); ++k) {
    std::fprintf(file, "%.10g", trajectory.t[k]);
    for (const std::vector<double>& column : trajectory.columns) {
      if (std::isnan(column[k])) {
        std::fputc(',', file);
      } else {
        std::fprintf(file, ",%.12g", column[k]);
      }
    }
    std::fputc('\n', file);
  }
  if (std::fclose(file) != 0 || std::rename(temporary.c_str(), path.c_str()) != 0) {
    *error = path + ": write failed";
    return false;
  }
  return true;
}

}  // namespace vesselid

#include "engine/data/resample.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/base/nan.h"

namespace vesselid {
namespace {

double MedianInterval(const std::vector<double>& t) {
  if (t.size() < 2) return 0.0;
  std::vector<double> steps;
  for (size_t k = 1; k < t.size(); ++k) steps.push_back(t[k] - t[k - 1]);
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  return steps[steps.size() / 2];
}

}  // namespace

bool Resample(const ResampleOptions& options, std::uint64_t max_rows, Trajectory* data,
              ResampleReport* report, std::string* error) {
  const double t0 = data->t.front(), t1 = data->t.back();
  const double count = std::floor((t1 - t0) * options.rate + 1e-6) + 1.0;
  if (!(count <= static_cast<double>(max_rows))) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  ": resampling %.6g s at %g Hz gives %.3g rows, more than the limit of %.3g",
                  t1 - t0, options.rate, count, static_cast<double>(max_rows));
    *error = data->source + text;
    return false;
  }
  const size_t n = static_cast<size_t>(count);
  std::vector<double> grid(n);
  for (size_t k = 0; k < n; ++k) grid[k] = t0 + static_cast<double>(k) / options.rate;
  ResampleReport result;
  result.rows_before = data->t.size();
  result.rows_after = n;
  // Grid points in a gap of the log itself (no row for longer than max_gap median row
  // intervals: the logger was off, e.g. between segments) stay empty in every column.
  std::vector<bool> inside(n, false);
  {
    const double longest = options.max_gap * MedianInterval(data->t) * (1.0 + 1e-9);
    size_t j = 0;
    for (size_t k = 0; k < n; ++k) {
      while (j < data->t.size() && data->t[j] <= grid[k]) ++j;
      inside[k] = (j > 0 && data->t[j - 1] == grid[k]) ||
                  (j > 0 && j < data->t.size() && data->t[j] - data->t[j - 1] <= longest);
      if (!inside[k]) ++result.outside;
    }
  }
  std::vector<std::vector<double>> columns(data->columns.size(), std::vector<double>(n, kNaN));
  for (size_t c = 0; c < data->columns.size(); ++c) {
    Channel channel = ExtractChannel(*data, static_cast<int>(c));
    if (channel.t.empty()) continue;
    const auto interpolated = options.interpolated.find(data->names[c]);
    std::vector<double>& out = columns[c];
    if (interpolated == options.interpolated.end()) {
      // Zero-order hold: the last sample at or before each grid time.
      size_t j = 0;
      for (size_t k = 0; k < n; ++k) {
        while (j < channel.t.size() && channel.t[j] <= grid[k]) ++j;
        if (j > 0 && inside[k]) out[k] = channel.value[j - 1];
      }
      continue;
    }
    const double period = interpolated->second;
    if (period > 0.0) {
      for (size_t j = 1; j < channel.value.size(); ++j) {
        const double d = channel.value[j] - channel.value[j - 1];
        channel.value[j] = channel.value[j - 1] + d - period * std::round(d / period);
      }
    }
    const double longest = options.max_gap * MedianInterval(channel.t) * (1.0 + 1e-9);
    int empty = 0;
    size_t j = 0;  // channel.t[j] is the first sample after grid[k]
    for (size_t k = 0; k < n; ++k) {
      while (j < channel.t.size() && channel.t[j] <= grid[k]) ++j;
      if (!inside[k]) continue;
      if (j > 0 && channel.t[j - 1] == grid[k]) {
        out[k] = channel.value[j - 1];
        continue;
      }
      const bool inside = j > 0 && j < channel.t.size();
      if (inside && channel.t[j] - channel.t[j - 1] <= longest) {
        const double w = (grid[k] - channel.t[j - 1]) / (channel.t[j] - channel.t[j - 1]);
        out[k] = channel.value[j - 1] + w * (channel.value[j] - channel.value[j - 1]);
      } else if (inside) {
        ++empty;
      }
    }
    if (empty > 0) result.left_empty[data->names[c]] = empty;
  }
  std::vector<int> lines(n, 0);
  if (!data->line.empty()) {
    size_t j = 0;
    for (size_t k = 0; k < n; ++k) {
      while (j + 1 < data->t.size() && data->t[j + 1] <= grid[k]) ++j;
      lines[k] = data->line[j];
    }
  }
  data->t = std::move(grid);
  data->columns = std::move(columns);
  data->line = std::move(lines);
  *report = std::move(result);
  return true;
}

}  // namespace vesselid

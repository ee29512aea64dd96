#include "engine/data/glitch_screen.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/base/nan.h"

namespace vesselid {
namespace {

constexpr double kNoiseAllowance = 7.0;  // sigmas of noise a step may carry beyond the rate
constexpr int kRelock = 5;               // consistent rejected samples in a row that are the track

// One screened channel: one column, or the position pair (distance in the plane).
struct Series {
  std::string name;
  std::vector<std::vector<double>*> columns;  // one or two
  double max_rate = 0.0;
  double period = 0.0;

  bool Present(size_t k) const {
    for (const auto* c : columns) {
      if (std::isnan((*c)[k])) return false;
    }
    return true;
  }
  bool Same(size_t a, size_t b) const {
    for (const auto* c : columns) {
      if ((*c)[a] != (*c)[b]) return false;
    }
    return true;
  }
  double Difference(const std::vector<double>& c, size_t a, size_t b) const {
    double d = c[b] - c[a];
    if (period > 0.0) d -= period * std::round(d / period);
    return d;
  }
  // Distance from sample a to sample b.
  double Distance(size_t a, size_t b) const {
    double sum = 0.0;
    for (const auto* c : columns) sum += std::pow(Difference(*c, a, b), 2);
    return std::sqrt(sum);
  }
  void Remove(size_t k) {
    for (auto* c : columns) (*c)[k] = kNaN;
  }
};

std::vector<size_t> PresentRows(const Series& s, size_t rows) {
  std::vector<size_t> present;
  for (size_t k = 0; k < rows; ++k) {
    if (s.Present(k)) present.push_back(k);
  }
  return present;
}

// Noise level from the median absolute second difference (per coordinate, the largest):
// sigma = 1.4826 MAD / sqrt(6), robust to the glitches themselves.
double RobustNoise(const Series& s, const std::vector<size_t>& rows) {
  double sigma = 0.0;
  for (const auto* c : s.columns) {
    std::vector<double> d2;
    for (size_t i = 2; i < rows.size(); ++i) {
      d2.push_back(std::abs(s.Difference(*c, rows[i - 1], rows[i]) -
                            s.Difference(*c, rows[i - 2], rows[i - 1])));
    }
    if (d2.empty()) continue;
    std::nth_element(d2.begin(), d2.begin() + d2.size() / 2, d2.end());
    sigma = std::max(sigma, 1.4826 * d2[d2.size() / 2] / std::sqrt(6.0));
  }
  return sigma;
}

void ScreenStale(const std::vector<Series>& all, size_t index, int stale, const Trajectory& data,
                 GlitchFinding* finding) {
  Series s = all[index];
  const std::vector<size_t> rows = PresentRows(s, data.t.size());
  // Whether another channel changes between rows a and b.
  auto others_change = [&](size_t a, size_t b) {
    for (size_t j = 0; j < all.size(); ++j) {
      if (j == index) continue;
      size_t first = b + 1;
      for (size_t k = a; k <= b; ++k) {
        if (!all[j].Present(k)) continue;
        if (first > b)
          first = k;
        else if (!all[j].Same(first, k))
          return true;
      }
    }
    return false;
  };
  size_t begin = 0;
  for (size_t i = 1; i <= rows.size(); ++i) {
    if (i < rows.size() && s.Same(rows[begin], rows[i])) continue;
    const size_t length = i - begin;
    if (length >= static_cast<size_t>(stale) && others_change(rows[begin], rows[i - 1])) {
      for (size_t j = begin + 1; j < i; ++j) {
        finding->Add(data.t[rows[j]]);
        s.Remove(rows[j]);
      }
    }
    begin = i;
  }
}

void ScreenJumps(Series s, const Trajectory& data, GlitchFinding* jumps, GlitchFinding* anchors) {
  const std::vector<size_t> rows = PresentRows(s, data.t.size());
  if (rows.size() < 2) return;
  const double allowance = kNoiseAllowance * RobustNoise(s, rows);
  auto within = [&](size_t a, size_t b) {
    return s.Distance(a, b) <= s.max_rate * (data.t[b] - data.t[a]) + allowance;
  };
  size_t last = rows[0];
  bool first_kept = false;  // a row after the first was within reach of it
  std::vector<size_t> rejected;  // consecutive rejected rows, each consistent with the one before
  for (size_t i = 1; i < rows.size(); ++i) {
    const size_t k = rows[i];
    if (within(last, k)) {
      first_kept = true;
      for (size_t r : rejected) {
        jumps->Add(data.t[r]);
        s.Remove(r);
      }
      rejected.clear();
      last = k;
      continue;
    }
    if (!rejected.empty() && !within(rejected.back(), k)) {
      for (size_t r : rejected) {
        jumps->Add(data.t[r]);
        s.Remove(r);
      }
      rejected.clear();
    }
    rejected.push_back(k);
    if (static_cast<int>(rejected.size()) >= kRelock) {
      if (!first_kept) {
        // Nothing ever followed the first row: it was the glitch (a logger's first row), not
        // a lasting move of the track.
        jumps->Add(data.t[rows[0]]);
        s.Remove(rows[0]);
        first_kept = true;
      } else {
        anchors->Add(data.t[rejected.front()]);
      }
      last = k;
      rejected.clear();
    }
  }
  for (size_t r : rejected) {
    jumps->Add(data.t[r]);
    s.Remove(r);
  }
}

std::string Seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", t);
  return text;
}

}  // namespace

std::vector<GlitchFinding> ScreenGlitches(const GlitchScreenOptions& options, Trajectory* data) {
  std::vector<Series> series;
  const bool pair = !options.north_column.empty();
  if (pair) {
    Series p;
    p.name = options.north_column + "/" + options.east_column;
    p.columns = {&data->columns[data->Find(options.north_column)],
                 &data->columns[data->Find(options.east_column)]};
    p.max_rate = options.max_speed;
    series.push_back(p);
  }
  for (const GlitchScreenOptions::Channel& c : options.channels) {
    Series s;
    s.name = c.column;
    s.columns = {&data->columns[data->Find(c.column)]};
    s.max_rate = c.max_rate;
    s.period = c.period;
    series.push_back(s);
  }
  const size_t screened = series.size();
  // References only where no other screened channel can tell (a log of one output).
  for (const std::string& column : screened == 1 ? options.reference_columns
                                                 : std::vector<std::string>{}) {
    const int c = data->Find(column);
    if (c < 0) continue;
    Series s;
    s.name = column;
    s.columns = {&data->columns[c]};
    series.push_back(s);
  }
  std::vector<GlitchFinding> findings;
  auto finish = [&](GlitchFinding f) {
    if (f.count > 0) findings.push_back(std::move(f));
  };
  if (pair && options.zero_fix) {
    GlitchFinding zero{"zero fix", series[0].name};
    for (size_t k = 0; k < data->t.size(); ++k) {
      if ((*series[0].columns[0])[k] == 0.0 && (*series[0].columns[1])[k] == 0.0) {
        zero.Add(data->t[k]);
        series[0].Remove(k);
      }
    }
    finish(zero);
  }
  if (options.stale >= 2) {
    for (size_t i = 0; i < screened; ++i) {
      GlitchFinding stale{"stale repeat", series[i].name};
      ScreenStale(series, i, options.stale, *data, &stale);
      finish(stale);
    }
  }
  for (size_t i = 0; i < screened; ++i) {
    const Series& s = series[i];
    if (!(s.max_rate > 0.0)) continue;
    GlitchFinding jumps{"jump", s.name}, anchors{"re-anchored", s.name};
    ScreenJumps(s, *data, &jumps, &anchors);
    finish(jumps);
    finish(anchors);
  }
  return findings;
}

std::string DescribeGlitches(const std::vector<GlitchFinding>& findings) {
  std::string text;
  for (const GlitchFinding& f : findings) {
    if (!text.empty()) text += "; ";
    std::string what;
    if (f.kind == "zero fix") {
      what = " zero fix(es) (0/0) of ";
    } else if (f.kind == "stale repeat") {
      what = " stale repeat(s) of ";
    } else if (f.kind == "jump") {
      what = " jump(s) faster than the screen's bound in ";
    } else {
      what = " lasting move(s) kept as the track (screen re-anchored) in ";
    }
    text += std::to_string(f.count) + what + f.channel + " (t = ";
    for (size_t i = 0; i < f.first_times.size(); ++i) {
      text += (i > 0 ? ", " : "") + Seconds(f.first_times[i]);
    }
    text += f.count > static_cast<int>(f.first_times.size()) ? ", ... s)" : " s)";
  }
  return text;
}

}  // namespace vesselid

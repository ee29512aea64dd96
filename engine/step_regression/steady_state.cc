#include "engine/step_regression/steady_state.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/base/check.h"
#include "engine/base/nan.h"

namespace vesselid {
namespace {

bool IsFiniteNonNegative(double x) { return std::isfinite(x) && x >= 0.0; }

// Mean and sample SD (n - 1; 0 for one sample) of the finite values of column `i` over rows
// [begin, end); NaN for both without values.
void MeanAndSd(const Eigen::MatrixXd& signals, int i, int begin, int end, double* mean,
               double* sd) {
  double sum = 0.0;
  int count = 0;
  for (int k = begin; k < end; ++k) {
    const double y = signals(k, i);
    if (std::isnan(y)) continue;
    sum += y;
    ++count;
  }
  if (count == 0) {
    *mean = *sd = kNaN;
    return;
  }
  *mean = sum / count;
  double squares = 0.0;
  for (int k = begin; k < end; ++k) {
    const double y = signals(k, i);
    if (std::isnan(y)) continue;
    squares += (y - *mean) * (y - *mean);
  }
  *sd = count > 1 ? std::sqrt(squares / (count - 1)) : 0.0;
}

// Fills the settle window, band, mean and SD of one interval.
void AnalyseInterval(const std::vector<double>& t, const Eigen::MatrixXd& signals,
                     const SteadyStateOptions& options, InputInterval* interval) {
  const int begin = interval->begin, end = interval->end, s = static_cast<int>(signals.cols());
  const int rows = end - begin;
  const double half_width = 0.5 * options.smoothing;

  // The interval's last half H.
  const double t_half = 0.5 * (interval->t_begin + interval->t_end);
  const int half_begin =
      static_cast<int>(std::lower_bound(t.begin() + begin, t.begin() + end, t_half) - t.begin());

  // Centred moving-average window [lo_k, hi_k) of each row, shared by all signals.
  std::vector<int> lo(rows), hi(rows);
  {
    int a = begin, b = begin;
    for (int k = begin; k < end; ++k) {
      while (t[a] < t[k] - half_width) ++a;
      while (b < end && t[b] <= t[k] + half_width) ++b;
      lo[k - begin] = a;
      hi[k - begin] = b;
    }
  }

  interval->band.assign(s, kNaN);
  // violated[k - begin]: some testable signal's smoothed value is outside its band at row k.
  std::vector<char> violated(rows, 0);
  std::vector<double> sum(rows + 1);
  std::vector<int> count(rows + 1);
  bool any_testable = false;
  for (int i = 0; i < s; ++i) {
    double reference, sd;
    MeanAndSd(signals, i, half_begin, end, &reference, &sd);
    if (std::isnan(reference)) continue;  // no samples in H: untestable
    any_testable = true;
    const double floor = options.tolerance.empty() ? 0.0 : options.tolerance[i];
    const double band = std::max(floor, options.band_factor * sd);
    interval->band[i] = band;
    // Prefix sums over the interval, relative to the reference for accuracy.
    sum[0] = 0.0;
    count[0] = 0;
    for (int k = begin; k < end; ++k) {
      const double y = signals(k, i);
      const bool valid = !std::isnan(y);
      sum[k - begin + 1] = sum[k - begin] + (valid ? y - reference : 0.0);
      count[k - begin + 1] = count[k - begin] + (valid ? 1 : 0);
    }
    for (int r = 0; r < rows; ++r) {
      const int a = lo[r] - begin, b = hi[r] - begin;
      const int c = count[b] - count[a];
      // Near or in a gap an average of a few samples is as noisy as the raw signal: a row is
      // tested only if at least half of its window's rows hold samples.
      if (c == 0 || 2 * c < b - a) continue;
      const double deviation = (sum[b] - sum[a]) / c;
      if (std::abs(deviation) > band) violated[r] = 1;
    }
  }

  if (!any_testable) {
    interval->steady_begin = end;
  } else {
    int r = rows;
    while (r > 0 && !violated[r - 1]) --r;
    interval->steady_begin = begin + r;
  }
  interval->t_steady = interval->steady_begin < end ? t[interval->steady_begin] : interval->t_end;
  interval->steady = any_testable && interval->steady_begin < end &&
                     interval->t_end - interval->t_steady >= options.min_duration;

  interval->mean.assign(s, kNaN);
  interval->sd.assign(s, kNaN);
  if (!interval->steady) return;
  for (int i = 0; i < s; ++i) {
    MeanAndSd(signals, i, interval->steady_begin, end, &interval->mean[i], &interval->sd[i]);
  }
}

}  // namespace

bool SteadyStateOptions::IsValid(std::string* error) const {
  if (!IsFiniteNonNegative(input_tolerance)) {
    *error = "input_tolerance must be finite and >= 0";
  } else if (!IsFiniteNonNegative(smoothing)) {
    *error = "smoothing must be finite and >= 0 (seconds)";
  } else if (!IsFiniteNonNegative(band_factor)) {
    *error = "band_factor must be finite and >= 0";
  } else if (!IsFiniteNonNegative(min_duration)) {
    *error = "min_duration must be finite and >= 0 (seconds)";
  } else {
    for (size_t i = 0; i < tolerance.size(); ++i) {
      if (!IsFiniteNonNegative(tolerance[i])) {
        *error = "tolerance[" + std::to_string(i) + "] must be finite and >= 0";
        return false;
      }
    }
    return true;
  }
  return false;
}

bool FindSteadyStates(const std::vector<double>& t, const Eigen::MatrixXd& signals,
                      const Eigen::MatrixXd& inputs, const SteadyStateOptions& options,
                      std::vector<InputInterval>* intervals, std::string* error) {
  VESSELID_CHECK(intervals != nullptr && error != nullptr);
  intervals->clear();
  if (!options.IsValid(error)) {
    *error = "steady-state options: " + *error;
    return false;
  }
  const int n = static_cast<int>(t.size());
  const int s = static_cast<int>(signals.cols()), q = static_cast<int>(inputs.cols());
  if (n == 0) {
    *error = "steady states: the record has no rows";
    return false;
  }
  if (signals.rows() != n || inputs.rows() != n) {
    *error = "steady states: " + std::to_string(n) + " times but " +
             std::to_string(signals.rows()) + " signal rows and " + std::to_string(inputs.rows()) +
             " input rows";
    return false;
  }
  if (s == 0 || q == 0) {
    *error = "steady states: need at least one signal and one input column";
    return false;
  }
  if (!options.tolerance.empty() && static_cast<int>(options.tolerance.size()) != s) {
    *error = "steady states: tolerance has " + std::to_string(options.tolerance.size()) +
             " entries for " + std::to_string(s) + " signals";
    return false;
  }
  for (int k = 0; k < n; ++k) {
    if (!std::isfinite(t[k])) {
      *error = "steady states: time at row " + std::to_string(k) + " is not finite";
      return false;
    }
    if (k > 0 && !(t[k] > t[k - 1])) {
      *error = "steady states: times are not strictly increasing at row " + std::to_string(k);
      return false;
    }
    for (int j = 0; j < q; ++j) {
      if (!std::isfinite(inputs(k, j))) {
        *error = "steady states: input " + std::to_string(j) + " at row " + std::to_string(k) +
                 " is not finite";
        return false;
      }
    }
    for (int i = 0; i < s; ++i) {
      if (std::isinf(signals(k, i))) {
        *error = "steady states: signal " + std::to_string(i) + " at row " + std::to_string(k) +
                 " is infinite (use NaN for a missing sample)";
        return false;
      }
    }
  }

  int begin = 0;
  for (int k = 1; k <= n; ++k) {
    bool change = k == n;
    for (int j = 0; j < q && !change; ++j) {
      change = std::abs(inputs(k, j) - inputs(begin, j)) > options.input_tolerance;
    }
    if (!change) continue;
    InputInterval interval;
    interval.begin = begin;
    interval.end = k;
    interval.t_begin = t[begin];
    interval.t_end = t[k - 1];
    interval.input.resize(q);
    for (int j = 0; j < q; ++j) interval.input[j] = inputs(begin, j);
    AnalyseInterval(t, signals, options, &interval);
    intervals->push_back(std::move(interval));
    begin = k;
  }
  return true;
}

}  // namespace vesselid

#include "engine/diagnose/record_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace vesselid {
namespace {

constexpr double kGridShare = 0.95;       // gaps on the grid
constexpr double kDistinctShare = 0.2;    // distinct values per sample at most
constexpr double kRoundOff = 1e-9;        // relative difference of values taken as equal
constexpr double kMidManoeuvre = 0.4;     // |first sample| / largest |sample| of an angle input
constexpr size_t kFewestSamples = 20;     // shorter columns are not judged
constexpr double kGapSteps = 3.0;         // median sample intervals that make a gap
constexpr size_t kStaleRun = 3;           // equal samples in a row that may be stale
constexpr double kStaleShare = 0.01;      // held samples per sample that make a finding

std::string Number4(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", value);
  return text;
}

// Samples of column `c` held in runs of kStaleRun or more equal values (not 0: a channel at
// rest) while one of the `others` changes, among its samples in [t0, t1]; *present gets the
// channel's sample count there.
int StaleSamples(const Trajectory& data, int c, const std::vector<int>& others, double t0,
                 double t1, int* present) {
  std::vector<size_t> rows;
  for (size_t k = 0; k < data.t.size(); ++k) {
    if (data.t[k] >= t0 - 1e-9 && data.t[k] <= t1 + 1e-9 && !std::isnan(data.columns[c][k])) {
      rows.push_back(k);
    }
  }
  *present = static_cast<int>(rows.size());
  const auto changes = [&](size_t a, size_t b) {
    for (int o : others) {
      double first = std::numeric_limits<double>::quiet_NaN();
      for (size_t k = a; k <= b; ++k) {
        const double v = data.columns[o][k];
        if (std::isnan(v)) continue;
        if (std::isnan(first)) first = v;
        if (v != first) return true;
      }
    }
    return false;
  };
  int held = 0;
  size_t begin = 0;
  for (size_t i = 1; i <= rows.size(); ++i) {
    const double value = data.columns[c][rows[begin]];
    if (i < rows.size() && data.columns[c][rows[i]] == value) continue;
    if (i - begin >= kStaleRun && value != 0.0 && changes(rows[begin], rows[i - 1])) {
      held += static_cast<int>(i - begin - 1);
    }
    begin = i;
  }
  return held;
}

}  // namespace

double QuantisationStep(const std::vector<double>& values) {
  if (values.size() < kFewestSamples) return 0.0;
  std::vector<double> distinct = values;
  std::sort(distinct.begin(), distinct.end());
  // Values apart by round-off only (a column converted from degrees, 1e-12 of its size) are
  // one value: a grid of round-off is no quantisation.
  const double scale = std::max(std::abs(distinct.front()), std::abs(distinct.back()));
  const double same = kRoundOff * scale;
  distinct.erase(std::unique(distinct.begin(), distinct.end(),
                             [same](double a, double b) { return b - a <= same; }),
                 distinct.end());
  if (distinct.size() < 3 || distinct.size() > kDistinctShare * values.size()) return 0.0;
  std::vector<double> gaps;
  for (size_t i = 1; i < distinct.size(); ++i) gaps.push_back(distinct[i] - distinct[i - 1]);
  const double q = *std::min_element(gaps.begin(), gaps.end());
  if (!(q > same)) return 0.0;
  size_t on_grid = 0;
  for (double g : gaps) {
    const double multiple = g / q;
    on_grid += std::abs(multiple - std::round(multiple)) <= 1e-3 * multiple;
  }
  return on_grid >= kGridShare * gaps.size() ? q : 0.0;
}

// stale_repeats for output `name` (column `column`) of `spec`, through `add`.
template <typename Add>
void AddStaleFinding(const ExperimentSpec& spec, const std::string& column, const std::string& name,
                     TrajectoryCache* cache, const Add& add) {
  std::string error;
  const Trajectory* data = LoadCachedTrajectory(spec, cache, &error);
  if (data == nullptr || data->Find(column) < 0) return;
  std::vector<int> others;
  for (const auto* map : {&spec.inputs, &spec.outputs}) {
    for (const auto& [channel, other] : *map) {
      const int o = data->Find(other);
      if (other != column && o >= 0) others.push_back(o);
    }
  }
  int present = 0;
  const int held = StaleSamples(*data, data->Find(column), others, spec.t_begin, spec.t_end, &present);
  if (held < 3 || held < kStaleShare * present) return;
  add(FindingKind::kStaleRepeats, name, held,
      "column '" + column + "' holds its value in " + std::to_string(held) + " of " +
          std::to_string(present) + " samples (runs of " + std::to_string(kStaleRun) +
          " or more equal samples while other columns change): a sensor or logger that repeated "
          "its last value; screen: {stale: " + std::to_string(kStaleRun) + "} removes them");
}

// gaps for output `name` (column `column`) of `spec`: steps between its samples longer than
// kGapSteps median steps, through `add`.
template <typename Add>
void AddGapFinding(const ExperimentSpec& spec, const std::string& column, const std::string& name,
                   TrajectoryCache* cache, const Add& add) {
  std::string error;
  const Trajectory* data = LoadCachedTrajectory(spec, cache, &error);
  if (data == nullptr || data->Find(column) < 0) return;
  // Rows with a sample in the window; with a segment column, steps between segments (the
  // logger off between them by design) are not gaps.
  const int c = data->Find(column),
            segment = spec.segments.column.empty() ? -1 : data->Find(spec.segments.column);
  double last_segment = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> t;
  std::vector<bool> same_segment;  // per step
  for (size_t k = 0; k < data->t.size(); ++k) {
    if (std::isnan(data->columns[c][k]) || data->t[k] < spec.t_begin - 1e-9 ||
        data->t[k] > spec.t_end + 1e-9) {
      continue;
    }
    if (!t.empty()) {
      same_segment.push_back(segment < 0 || data->columns[segment][k] == last_segment);
    }
    t.push_back(data->t[k]);
    if (segment >= 0) last_segment = data->columns[segment][k];
  }
  if (t.size() < kFewestSamples) return;
  std::vector<double> steps(t.size() - 1);
  for (size_t k = 1; k < t.size(); ++k) steps[k - 1] = t[k] - t[k - 1];
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  int gaps = 0;
  double longest = 0.0;
  std::string where;
  for (size_t k = 0; k < steps.size(); ++k) {
    if (!(steps[k] > kGapSteps * median) || !same_segment[k]) continue;
    if (++gaps <= 3) {
      where +=
          (where.empty() ? "" : ", ") + Number4(steps[k]) + " s at t = " + Number4(t[k]) + " s";
    }
    longest = std::max(longest, steps[k]);
  }
  if (gaps == 0) return;
  add(FindingKind::kGaps, name, longest,
      "column '" + column + "' has " + std::to_string(gaps) + " gap(s) longer than " +
          Number4(kGapSteps) + " median sample intervals (" + Number4(median) + " s): " + where +
          (gaps > 3 ? ", ..." : ""));
}

void AddRecordCheckFindings(const RunConfig& config, TrajectoryCache* cache,
                            std::vector<Finding>* findings) {
  const ModelInfo& info = config.model->info();
  for (const ExperimentSpec& spec : config.experiments) {
    auto add = [&](FindingKind kind, const std::string& channel, double value,
                   const std::string& message) {
      Finding f = MakeFinding(kind, message);
      f.experiment = spec.name;
      (spec.inputs.count(channel) > 0 ? f.input : f.output) = channel;
      f.value = value;
      findings->push_back(std::move(f));
    };
    std::vector<std::pair<std::string, std::string>> channels;  // (model name, column)
    for (const auto& [input, column] : spec.inputs) channels.emplace_back(input, column);
    const size_t inputs = channels.size();
    for (const auto& [output, column] : spec.outputs) channels.emplace_back(output, column);
    for (size_t c = 0; c < channels.size(); ++c) {
      const auto& [name, column] = channels[c];
      std::vector<double> values;
      if (!WindowSamples(spec, column, cache, &values) || values.size() < kFewestSamples) continue;
      const bool degrees = spec.IsDegreeColumn(column);
      const double unit = degrees ? 180.0 / M_PI : 1.0;
      const std::string label = degrees ? " deg" : "";
      const auto [low, high] = std::minmax_element(values.begin(), values.end());
      if (c < inputs && *low == 0.0 && *high == 0.0) {
        add(FindingKind::kAllZeroInput, name, 0.0,
            "column '" + column + "' is 0 in all " + std::to_string(values.size()) +
                " samples: what the input drives cannot be identified from this record");
        continue;
      }
      const double q = QuantisationStep(values);
      if (q > 0.0) {
        add(FindingKind::kQuantised, name, q * unit,
            "column '" + column + "' is quantised in steps of " + Number4(q * unit) + label +
                ": its noise is at least " + Number4(q * unit / std::sqrt(12.0)) + label);
      } else if (c >= inputs) {
        AddStaleFinding(spec, column, name, cache, add);
      }
      if (c >= inputs) AddGapFinding(spec, column, name, cache, add);
      const int input = info.InputIndex(name);
      if (c < inputs && input >= 0 && info.InputUnit(input) == "rad") {
        const double largest = std::max(std::abs(*low), std::abs(*high));
        const double share = std::abs(values.front()) / largest;
        if (share >= kMidManoeuvre) {
          add(FindingKind::kStartsMidManoeuvre, name, values.front() * unit,
              "column '" + column + "' starts at " + Number4(values.front() * unit) + label + ", " +
                  Number4(100.0 * share) + " % of its largest magnitude " +
                  Number4(largest * unit) + label + ": the record starts mid-manoeuvre");
        }
      }
    }
  }
}

}  // namespace vesselid

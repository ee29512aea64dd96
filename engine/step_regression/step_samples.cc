#include "engine/step_regression/step_samples.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "engine/base/elapsed.h"

namespace vesselid {
namespace {

// Group ids by key: the same input levels in the same record share one.
class Groups {
 public:
  int Id(const std::string& record, int term, double a, double b) {
    auto key = std::make_tuple(record, term, std::llround(a * 1e6), std::llround(b * 1e6));
    auto found = ids_.find(key);
    if (found != ids_.end()) return found->second;
    const int id = static_cast<int>(ids_.size());
    ids_[key] = id;
    return id;
  }

 private:
  std::map<std::tuple<std::string, int, long long, long long>, int> ids_;
};

bool Inside(const StepSampleOptions& o, int i, double level) {
  return level >= o.input_lower[i] - 1e-9 && level <= o.input_upper[i] + 1e-9;
}

}  // namespace

bool StepSampleOptions::IsValid(const DampingInertiaForm& form, std::string* error) const {
  const size_t n = form.states.size();
  if (input_lower.size() != n || input_upper.size() != n || min_change.size() != n) {
    *error = "step samples: input ranges and min_change need one value per regressed state";
    return false;
  }
  for (size_t i = 0; i < n; ++i) {
    if (!(input_lower[i] <= input_upper[i])) {
      *error = "step samples: inverted input range";
      return false;
    }
    if (!(min_change[i] > 0.0)) {
      *error = "step samples: min_change must be > 0";
      return false;
    }
  }
  if (!(fit_horizon > 0.0)) {
    *error = "step samples: fit_horizon must be > 0";
    return false;
  }
  return steady.IsValid(error) && step_fit.IsValid(error);
}

bool ExtractStepSamples(const DampingInertiaForm& form,
                        const std::vector<RegressionRecord>& records,
                        const StepSampleOptions& options, StepSamples* samples,
                        std::string* error) {
  if (form.states.size() != 2) {
    *error = "step samples: the damping-inertia form needs two regressed states";
    return false;
  }
  if (!options.IsValid(form, error)) return false;
  StepSamples out;
  Groups damping_groups, inertia_groups;
  const int turn = form.turning_state;
  int skipped_small = 0, skipped_range = 0, skipped_fit = 0, skipped_multi = 0;
  for (const RegressionRecord& record : records) {
    const int n = record.size();
    Eigen::MatrixXd signals(n, 2), inputs(n, 2);
    for (int i = 0; i < 2; ++i) {
      signals.col(i) = record.x.col(form.states[i]);
      inputs.col(i) = record.u.col(form.inputs[i]);
    }
    std::vector<InputInterval> intervals;
    auto start = SteadyClock::now();
    if (!FindSteadyStates(record.t, signals, inputs, options.steady, &intervals, error)) {
      *error = record.name + ": " + *error;
      return false;
    }
    out.window_seconds += SecondsSince(start);
    out.intervals += static_cast<int>(intervals.size());

    for (const InputInterval& v : intervals) {
      if (!v.steady) continue;
      ++out.steady;
      if (!Inside(options, 0, v.input[0]) || !Inside(options, 1, v.input[1])) continue;
      DampingSample s;
      s.record = record.name;
      s.t = v.t_steady;
      s.duration = v.t_end - v.t_steady;
      for (int i = 0; i < 2; ++i) {
        s.x[i] = v.mean[i];
        s.sigma[i] = v.input[i];
      }
      const bool straight = turn >= 0 && v.input[turn] == 0.0;
      if (turn >= 0) s.turns = std::abs(s.x[turn]) * s.duration / (2.0 * M_PI);
      if (straight && options.zero_straight) s.x[turn] = 0.0;
      if (options.turn_weights && turn >= 0 && !straight) {
        s.weight = s.turns >= 1.0 ? 1.0 : s.turns >= 0.5 ? 0.5 : 0.1;
      }
      s.group = damping_groups.Id(record.name, -1, v.input[0], v.input[1]);
      out.damping.push_back(s);
    }

    start = SteadyClock::now();
    for (size_t j = 1; j < intervals.size(); ++j) {
      const InputInterval& a = intervals[j - 1];
      const InputInterval& b = intervals[j];
      if (!a.steady || !b.steady) continue;
      int stepped = -1, changed = 0;
      for (int i = 0; i < 2; ++i) {
        if (std::abs(b.input[i] - a.input[i]) > options.steady.input_tolerance) {
          stepped = i;
          ++changed;
        }
      }
      if (changed != 1) {
        skipped_multi += changed > 1;
        continue;
      }
      ++out.steps;
      const int i = stepped;
      if (!Inside(options, 0, a.input[0]) || !Inside(options, 1, a.input[1]) ||
          !Inside(options, 0, b.input[0]) || !Inside(options, 1, b.input[1])) {
        ++skipped_range;
        continue;
      }
      if (!(std::abs(b.mean[i] - a.mean[i]) >= options.min_change[i])) {
        ++skipped_small;
        continue;
      }
      // The command changed between rows b.begin - 1 and b.begin.
      const double t_step =
          b.begin > 0 ? 0.5 * (record.t[b.begin - 1] + record.t[b.begin]) : record.t[b.begin];
      std::vector<double> t, y;
      for (int k = b.begin; k < b.end && record.t[k] <= t_step + options.fit_horizon; ++k) {
        t.push_back(record.t[k]);
        y.push_back(signals(k, i));
      }
      FirstOrderStepFit fit;
      std::string fit_error;
      if (!FitFirstOrderStep(t, y, t_step, a.mean[i], b.mean[i], b.input[i] - a.input[i],
                             options.step_fit, &fit, &fit_error) ||
          fit.at_bound || !(fit.inertia > 0.0)) {
        ++skipped_fit;
        continue;
      }
      InertiaSample s;
      s.record = record.name;
      s.term = i;
      s.t = t_step;
      for (int c = 0; c < 2; ++c) s.x[c] = 0.5 * (a.mean[c] + b.mean[c]);
      s.inertia = fit.inertia;
      s.gain = fit.gain;
      s.time_constant = fit.time_constant;
      s.rms = fit.rms;
      const double lo = std::min(a.input[i], b.input[i]), hi = std::max(a.input[i], b.input[i]);
      s.group = inertia_groups.Id(record.name + "|" + std::to_string(a.input[1 - i]), i, lo, hi);
      out.inertia[i].push_back(s);
    }
    out.fit_seconds += SecondsSince(start);
  }

  if (options.mirror && turn >= 0) {
    const size_t count = out.damping.size();
    for (size_t k = 0; k < count; ++k) {
      DampingSample m = out.damping[k];
      if (m.x[turn] == 0.0 && m.sigma[turn] == 0.0) continue;  // its own mirror image
      m.x[turn] = -m.x[turn];
      m.sigma[turn] = -m.sigma[turn];
      m.mirrored = true;
      out.damping.push_back(m);
    }
    for (auto& set : out.inertia) {
      const size_t n = set.size();
      for (size_t k = 0; k < n; ++k) {
        InertiaSample m = set[k];
        if (m.x[turn] == 0.0) continue;
        m.x[turn] = -m.x[turn];
        m.mirrored = true;
        set.push_back(m);
      }
    }
  }
  char line[200];
  std::snprintf(line, sizeof(line),
                "%d intervals, %d steady; %d single-input steps: %d outside the input ranges, "
                "%d too small, %d without a first-order fit; %d multi-input steps",
                out.intervals, out.steady, out.steps, skipped_range, skipped_small, skipped_fit,
                skipped_multi);
  out.notes.push_back(line);
  *samples = std::move(out);
  return true;
}

}  // namespace vesselid

#include "engine/regression/regression_data.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/base/format_numbers.h"
#include "engine/base/nan.h"

namespace vesselid {
namespace {

constexpr double kSampleTimeTolerance = 1e-9;

// Index of the last sample at or before t, or -1.
int LastAtOrBefore(const std::vector<double>& times, double t) {
  auto it = std::upper_bound(times.begin(), times.end(), t + kSampleTimeTolerance);
  return static_cast<int>(it - times.begin()) - 1;
}

double CausalValue(const Channel& c, double t) {
  const int j = LastAtOrBefore(c.t, t);
  if (j < 0) return c.value.front();  // before the first sample: its value
  if (std::abs(c.t[j] - t) <= kSampleTimeTolerance || j == 0) return c.value[j];
  const double slope = (c.value[j] - c.value[j - 1]) / (c.t[j] - c.t[j - 1]);
  return c.value[j] + slope * (t - c.t[j]);
}

Channel Window(const Channel& c, double t0, double t1) {
  Channel w;
  for (size_t k = 0; k < c.t.size(); ++k) {
    if (c.t[k] >= t0 - kSampleTimeTolerance && c.t[k] <= t1 + kSampleTimeTolerance) {
      w.t.push_back(c.t[k]);
      w.value.push_back(c.value[k]);
    }
  }
  return w;
}

}  // namespace

bool BuildRegressionRecord(const ExperimentSpec& spec, const Trajectory& data,
                           const ModelHandle& model, const RegressionDataOptions& options,
                           RegressionRecord* record, std::string* error) {
  auto fail = [&](const std::string& what) {
    *error = "experiment '" + spec.name + "' (" + data.source + "): " + what;
    return false;
  };
  const ModelInfo& info = model.info();
  const int nx = static_cast<int>(info.states.size());
  const int nu = static_cast<int>(info.inputs.size());
  const int ny = static_cast<int>(info.outputs.size());
  const double t0 = std::max(spec.t_begin, data.t.front());
  const double t1 = std::min(spec.t_end, data.t.back());

  // Output channels in the window (angles unwrapped), and the grid.
  std::vector<Channel> outputs(ny);
  std::vector<bool> mapped(ny, false);
  int grid = -1;
  for (const auto& [output, column_name] : spec.outputs) {
    const int index = info.OutputIndex(output);
    if (index < 0) return fail("unknown output '" + output + "'");
    const int column = data.Find(column_name);
    if (column < 0) return fail("no column '" + column_name + "' for output '" + output + "'");
    outputs[index] = Window(ExtractChannel(data, column), t0, t1);
    if (outputs[index].t.size() < 2) return fail("output '" + output + "' has < 2 samples");
    if (info.angle_outputs[index]) UnwrapAngles(&outputs[index].value);
    mapped[index] = true;
    if (options.grid_output.empty()) {
      if (grid < 0 || outputs[index].t.size() < outputs[grid].t.size()) grid = index;
    } else if (output == options.grid_output) {
      grid = index;
    }
  }
  if (grid < 0) return fail("grid output '" + options.grid_output + "' is not mapped");
  RegressionRecord r;
  r.name = spec.name;
  r.grid_output = grid;
  r.t = outputs[grid].t;
  const int n = r.size();
  std::vector<double> steps(n - 1);
  for (int k = 0; k + 1 < n; ++k) steps[k] = r.t[k + 1] - r.t[k];
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  r.dt = sorted[sorted.size() / 2];
  for (int k = 0; k + 1 < n; ++k) {
    const GridStep kind = GridStepOf(steps[k], r.dt, options.max_gap);
    if (kind == GridStep::kAccepted) continue;
    char text[160];
    std::snprintf(text, sizeof(text), "step of %g s (%.3g median steps) at t = %g s", steps[k],
                  steps[k] / r.dt, r.t[k]);
    if (kind == GridStep::kJitter) {
      return fail(std::string(text) + " in output '" + info.outputs[grid] +
                  "': row jitter beyond the stage's max_gap (" +
                  FormatNumbers("%g", options.max_gap) +
                  " median steps); raise max_gap to " +
                  FormatNumbers("%.2g", std::ceil(10.0 * steps[k] / r.dt) / 10.0) +
                  " or more");
    }
    return fail(std::string(text) + " in output '" + info.outputs[grid] +
                "': a gap of missing samples inside a piece (pieces are cut at gaps before "
                "they are built; cut the record into segments)");
  }


  // Inputs held, outputs causal, then smoothed values and rates.
  r.u.resize(n, nu);
  for (int i = 0; i < nu; ++i) {
    auto mapped_input = spec.inputs.find(info.inputs[i]);
    const int column = mapped_input == spec.inputs.end() ? -1 : data.Find(mapped_input->second);
    if (column < 0) return fail("input '" + info.inputs[i] + "' is not mapped to a column");
    const Channel c = ExtractChannel(data, column);
    if (c.t.empty()) return fail("input '" + info.inputs[i] + "' has no samples");
    for (size_t k = 0; k < c.t.size() && info.InputPositive(i); ++k) {
      if (!(c.value[k] > 0.0)) {
        return fail("input '" + info.inputs[i] + "' is " + std::to_string(c.value[k]) +
                    " at t = " + std::to_string(c.t[k]) + " s: the model needs it > 0");
      }
    }
    for (int k = 0; k < n; ++k) {
      const int j = LastAtOrBefore(c.t, r.t[k]);
      r.u(k, i) = c.value[std::max(j, 0)];
    }
  }
  Eigen::MatrixXd y = Eigen::MatrixXd::Constant(n, ny, kNaN);
  Eigen::MatrixXd ydot = Eigen::MatrixXd::Constant(n, ny, kNaN);
  SavitzkyGolayOptions sg = options.smoothing;
  std::vector<double> aligned(n), out;
  for (int o = 0; o < ny; ++o) {
    if (!mapped[o]) continue;
    for (int k = 0; k < n; ++k) aligned[k] = CausalValue(outputs[o], r.t[k]);
    for (int derivative = 0; derivative < 2; ++derivative) {
      sg.derivative = derivative;
      if (!SavitzkyGolay(aligned, r.dt, sg, &out, error)) return fail(*error);
      for (int k = 0; k < n; ++k) (derivative == 0 ? y : ydot)(k, o) = out[k];
    }
  }

  // States: outputs of the same name, then the model's guess from the rates.
  r.x = Eigen::MatrixXd::Zero(n, nx);
  std::vector<double> xrow(nx), yrow(ny), ydotrow(ny);
  for (int k = 0; k < n; ++k) {
    for (int s = 0; s < nx; ++s) {
      const int o = info.OutputIndex(info.states[s]);
      xrow[s] = o >= 0 && mapped[o] ? y(k, o) : 0.0;
    }
    for (int o = 0; o < ny; ++o) {
      yrow[o] = y(k, o);
      ydotrow[o] = ydot(k, o);
    }
    model.GuessState(yrow.data(), ydotrow.data(), xrow.data());
    for (int s = 0; s < nx; ++s) r.x(k, s) = xrow[s];
  }
  r.xdot.resize(n, nx);
  sg.derivative = 1;
  std::vector<double> column(n);
  for (int s = 0; s < nx; ++s) {
    for (int k = 0; k < n; ++k) column[k] = r.x(k, s);
    if (!SavitzkyGolay(column, r.dt, sg, &out, error)) return fail(*error);
    for (int k = 0; k < n; ++k) r.xdot(k, s) = out[k];
  }
  r.region.resize(n);
  for (int k = 0; k < n; ++k) {
    const Eigen::VectorXd row = r.u.row(k).transpose();
    r.region[k] = model.regression_form() ? model.Region(row.data()) : -1;
  }
  r.use.assign(n, true);
  *record = std::move(r);
  return true;
}

GridStep GridStepOf(double step, double median_step, double max_gap) {
  if (step <= max_gap * median_step * (1.0 + 1e-9)) return GridStep::kAccepted;
  return step >= kMissingSampleStep * median_step * (1.0 - 1e-9) ? GridStep::kGap
                                                                  : GridStep::kJitter;
}

}  // namespace vesselid

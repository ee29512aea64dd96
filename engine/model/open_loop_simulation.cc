#include "engine/model/open_loop_simulation.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/base/work_limits.h"
#include "engine/model/step_plan.h"

namespace vesselid {

bool SimulateOpenLoop(const ModelHandle& model, const std::vector<double>& parameters,
                      const std::vector<double>& initial_state, const Trajectory& inputs,
                      const OpenLoopOptions& options, Trajectory* result, std::string* error) {
  const ModelInfo& info = model.info();
  const int nx = static_cast<int>(info.states.size());
  const int nu = static_cast<int>(info.inputs.size());
  const int ny = static_cast<int>(info.outputs.size());
  if (static_cast<int>(initial_state.size()) != nx || parameters.size() != info.parameters.size()) {
    *error = "initial state or parameter vector has the wrong size for " + info.name;
    return false;
  }
  if (options.substeps < 0 || inputs.t.size() < 2) {
    *error = "need substeps >= 0 and at least two input samples";
    return false;
  }
  if (!(options.max_step >= 0.0 && std::isfinite(options.max_step))) {
    *error = "max_step " + std::to_string(options.max_step) +
             ": a step bound in s, >= 0 (0: the median sample interval)";
    return false;
  }
  const size_t samples = inputs.t.size();
  // Steps per sample interval.
  std::vector<int> steps(samples - 1, options.substeps);
  if (options.substeps == 0) {
    std::vector<double> intervals;
    for (size_t k = 0; k + 1 < samples; ++k) intervals.push_back(inputs.t[k + 1] - inputs.t[k]);
    const double bound = StepBound(intervals, options.max_step);
    double total = 0.0;
    for (size_t k = 0; k + 1 < samples; ++k) total += StepsIn(intervals[k], bound);
    if (!(bound > 0.0) || !(total <= static_cast<double>(WorkLimits().integration_steps))) {
      char text[200];
      std::snprintf(text, sizeof(text),
                    "steps of at most %g s over the inputs' %g s are %g, more than the limit of "
                    "%g integration steps",
                    bound, inputs.t.back() - inputs.t.front(), total,
                    static_cast<double>(WorkLimits().integration_steps));
      *error = text;
      return false;
    }
    for (size_t k = 0; k + 1 < samples; ++k) steps[k] = static_cast<int>(StepsIn(intervals[k], bound));
  }
  if (!options.input_interpolation.empty() && options.input_interpolation.size() != info.inputs.size()) {
    *error = "an interpolation per input of " + info.name + " is needed";
    return false;
  }
  // Input values at every step's start and midpoint.
  // Per step: start, midpoint, end (left limit: a held command switches at the next step).
  std::vector<double> times, ends;
  for (size_t k = 0; k + 1 < samples; ++k) {
    const int m = steps[k];
    const double h = (inputs.t[k + 1] - inputs.t[k]) / m;
    for (int s = 0; s < m; ++s) {
      times.push_back(inputs.t[k] + s * h);
      times.push_back(inputs.t[k] + (s + 0.5) * h);
      ends.push_back(s + 1 == m ? inputs.t[k + 1] : inputs.t[k] + (s + 1) * h);
    }
  }
  times.push_back(inputs.t.back());
  std::vector<std::vector<double>> u(nu), u_end(nu);
  for (int i = 0; i < nu; ++i) {
    const int column = inputs.Find(info.inputs[i]);
    if (column < 0) {
      if (!info.InputOptional(i)) {
        *error = "no input signal '" + info.inputs[i] + "'";
        return false;
      }
      u[i].assign(times.size(), std::numeric_limits<double>::quiet_NaN());
      u_end[i].assign(ends.size(), std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    const Channel channel = ExtractChannel(inputs, column);
    if (channel.t.empty()) {
      *error = "input '" + info.inputs[i] + "' has no samples (every value is missing)";
      return false;
    }
    const Interpolation method =
        options.input_interpolation.empty() ? options.interpolation : options.input_interpolation[i];
    u[i] = InterpolateAt(channel, method, times);
    u_end[i] = InterpolateAt(channel, method, ends, true);
  }

  Trajectory out;
  out.t = inputs.t;
  out.names = inputs.names;
  out.columns = inputs.columns;
  for (const std::string& name : info.outputs) {
    out.names.push_back(name);
    out.columns.emplace_back();
  }
  if (options.record_states) {
    for (const std::string& name : info.states) {
      out.names.push_back("x." + name);
      out.columns.emplace_back();
    }
  }
  const size_t first_output = inputs.names.size();
  const size_t first_state = first_output + info.outputs.size();
  std::vector<double> x = initial_state, k1(nx), k2(nx), k3(nx), k4(nx), xs(nx), y(ny), ut(nu);
  std::vector<double> ue(nu);
  auto input_at = [&](size_t j) {
    for (int i = 0; i < nu; ++i) ut[i] = u[i][j];
    return ut.data();
  };
  auto input_end = [&](size_t step) {
    for (int i = 0; i < nu; ++i) ue[i] = u_end[i][step];
    return ue.data();
  };
  size_t j = 0;  // index into `times`: 2 per step
  for (size_t k = 0; k < samples; ++k) {
    model.Output(x.data(), input_at(j), parameters.data(), y.data());
    for (int i = 0; i < ny; ++i) out.columns[first_output + i].push_back(y[i]);
    if (options.record_states) {
      for (int i = 0; i < nx; ++i) out.columns[first_state + i].push_back(x[i]);
    }
    if (k + 1 == samples) break;
    const int m = steps[k];
    const double h = (inputs.t[k + 1] - inputs.t[k]) / m;
    // Rk4Step's arithmetic, term for term (rk4.h).
    const double half_h = 0.5 * h, sixth_h = h / 6.0;
    for (int s = 0; s < m; ++s, j += 2) {
      bool ok = model.Derivative(x.data(), input_at(j), parameters.data(), k1.data());
      for (int i = 0; i < nx; ++i) xs[i] = x[i] + half_h * k1[i];
      ok = ok && model.Derivative(xs.data(), input_at(j + 1), parameters.data(), k2.data());
      for (int i = 0; i < nx; ++i) xs[i] = x[i] + half_h * k2[i];
      ok = ok && model.Derivative(xs.data(), input_at(j + 1), parameters.data(), k3.data());
      for (int i = 0; i < nx; ++i) xs[i] = x[i] + h * k3[i];
      ok = ok && model.Derivative(xs.data(), input_end(j / 2), parameters.data(), k4.data());
      for (int i = 0; i < nx; ++i) {
        x[i] += sixth_h * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
        ok = ok && std::isfinite(x[i]);
      }
      if (!ok) {
        char text[80];
        std::snprintf(text, sizeof(text), " simulation diverged at t = %.9g s", inputs.t[k] + s * h);
        *error = info.name + text;
        return false;
      }
    }
  }
  *result = std::move(out);
  return true;
}

}  // namespace vesselid

#include "engine/model/experiment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "engine/base/angle.h"
#include "engine/base/memory_budget.h"
#include "engine/base/statistics.h"
#include "engine/data/angle_units.h"
#include "engine/data/latent_input.h"
#include "engine/data/noise_level.h"
#include "engine/data/record_start.h"
#include "engine/model/step_plan.h"

namespace vesselid {
namespace {

constexpr double kNodeTimeTolerance = 1e-9;

// An output's column as a channel; an angle output not compared modulo one turn is unwrapped,
// and refused where two samples inside [t0, t_end] are too far apart to tell which way it
// turned (gaps outside the window, e.g. between the segments of a record, do not matter: the
// window's start value and samples move by the same whole turns).
bool OutputChannelOf(RecordChannels* channels, int column, const ModelInfo& info, int output,
                     bool wrapped, bool degrees, double t0, double t_end, const Channel** channel,
                     std::string* error) {
  const Trajectory& trajectory = channels->trajectory();
  *channel = &channels->Extracted(column);
  const bool angle =
      output < static_cast<int>(info.angle_outputs.size()) && info.angle_outputs[output];
  if (!angle || wrapped) return true;
  const std::vector<double>& raw = channels->Extracted(column).value;
  double largest = 0.0;
  *channel = &channels->Unwrapped(column, &largest);
  if (largest <= kMaxAngleStep) return true;
  const std::vector<double>& t = (*channel)->t;
  for (size_t k = 1; k < raw.size(); ++k) {
    const double step = WrapAngle(raw[k] - raw[k - 1]);
    const bool inside = t[k - 1] >= t0 - kNodeTimeTolerance && t[k] <= t_end + kNodeTimeTolerance;
    if (!inside || std::abs(step) <= kMaxAngleStep) continue;
    char text[400];
    std::snprintf(text, sizeof(text),
                  "angle output '%s' (column '%s') changes by %.0f deg between t = %g and %g: "
                  "the sampling cannot tell which way it turned, so it cannot be unwrapped; "
                  "list '%s' in the experiment's wrap: to compare it modulo one turn",
                  info.outputs[output].c_str(), trajectory.names[column].c_str(),
                  std::abs(step) * 180.0 / M_PI, t[k - 1], t[k], info.outputs[output].c_str());
    *error = text;
    // A column read in degrees is in radians here: the hint is for one that is not.
    const AngleUnitCheck unit = CheckAngleUnit(raw);
    if (unit.looks_like_degrees && !degrees)
      *error += "; " + DescribeDegreesLook(trajectory.names[column], unit);
    return false;
  }
  return true;
}

// The samples [first, last) of sorted times `t` with t0 - tol <= t <= t_end + tol: the same
// tests as a scan, found by bisection (a segment of a long record is a short window of it).
std::pair<size_t, size_t> InWindow(const std::vector<double>& t, double t0, double t_end) {
  const auto first = std::partition_point(
      t.begin(), t.end(), [&](double x) { return !(x >= t0 - kNodeTimeTolerance); });
  const auto last = std::partition_point(first, t.end(),
                                         [&](double x) { return x <= t_end + kNodeTimeTolerance; });
  return {static_cast<size_t>(first - t.begin()), static_cast<size_t>(last - t.begin())};
}

// The latent input of model input `index` (input_noise.h): the spline fitted to the samples
// in the window (and a few beyond it, so that its ends are held by data) evaluated at the step
// times, and the grid of its corrections.
bool FitLatentInput(const ExperimentSpec& spec, const std::string& input,
                    const std::string& column, int index, const Channel& channel, double t0,
                    double t_end, const std::vector<double>& right_times,
                    const std::vector<double>& end_times, Experiment* e,
                    std::vector<double>* right, std::vector<double>* end, std::string* error) {
  const InputNoiseSpec& noise = spec.input_noise.at(input);
  constexpr int kPad = 20;
  const auto first = std::lower_bound(channel.t.begin(), channel.t.end(), t0 - kNodeTimeTolerance);
  const auto last =
      std::upper_bound(channel.t.begin(), channel.t.end(), t_end + kNodeTimeTolerance);
  const long lo = std::max(0L, static_cast<long>(first - channel.t.begin()) - kPad);
  const long hi = std::min(static_cast<long>(channel.t.size()),
                           static_cast<long>(last - channel.t.begin()) + kPad);
  Channel window;
  window.t.assign(channel.t.begin() + lo, channel.t.begin() + hi);
  window.value.assign(channel.value.begin() + lo, channel.value.begin() + hi);
  const bool degrees = spec.IsDegreeColumn(column);
  const double unit = degrees ? M_PI / 180.0 : 1.0;
  LatentInputSpline spline;
  if (!spline.Fit(window, {noise.sigma * unit, noise.knots}, error)) return false;
  *right = spline.At(right_times);
  *end = spline.At(end_times);
  LatentInput latent;
  latent.input = index;
  latent.column = column;
  latent.degrees = degrees;
  latent.sigma = spline.sigma();
  latent.sigma_estimated = !(noise.sigma > 0.0);
  NoiseLevel level;
  for (double v : window.value) level.Add(v);
  latent.noise_level = level.Sigma();
  latent.knot_spacing = spline.knot_spacing();
  latent.sample_interval = spline.sample_interval();
  latent.samples = spline.samples();
  e->latent_inputs.push_back(latent);
  if (noise.correction < 0.0) return true;

  // Corrections: at most kMaxInputCorrections, each over at least kMinCorrectionSamples.
  const double length = t_end - t0, dt = latent.sample_interval;
  const double spacing =
      noise.correction > 0.0
          ? noise.correction
          : std::max(length / kMaxInputCorrections, kMinCorrectionSamples * dt);
  if (spacing < kMinCorrectionSamples * dt) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "correction spacing %g s is shorter than %g input samples (%g s)", spacing,
                  kMinCorrectionSamples, kMinCorrectionSamples * dt);
    *error = text;
    return false;
  }
  InputCorrectionGrid grid;
  grid.input = index;
  grid.spacing = spacing;
  grid.count = std::max(1, static_cast<int>(std::ceil(length / spacing - 1e-9)));
  grid.offset = e->num_input_corrections();
  grid.sigma = latent.sigma * std::sqrt(dt / spacing);
  const size_t steps = end_times.size();
  grid.step_interval.resize(steps);
  for (size_t s = 0; s < steps; ++s) {
    const int j = static_cast<int>(std::floor((right_times[2 * s] - t0) / spacing));
    grid.step_interval[s] = std::clamp(j, 0, grid.count - 1);
  }
  e->input_corrections.push_back(std::move(grid));
  return true;
}

// The experiment's time window within its record.
struct Window {
  double t0, t_end;
};

// A selected output and the channel of its column.
struct OutputChannel {
  int output;
  double weight;
  const Channel* channel;
};

// The outputs compared (options.outputs, else every mapped one) and their channels; the
// wrapped outputs marked in `e`. False with `what` (without the experiment's name).
bool SelectOutputs(const ExperimentSpec& spec, RecordChannels* record_channels,
                   const ModelInfo& info, const ExperimentOptions& options, const Window& window,
                   Experiment* e, std::vector<OutputChannel>* channels, std::string* what) {
  const Trajectory& trajectory = record_channels->trajectory();
  std::vector<std::string> selected = options.outputs;
  if (selected.empty()) {
    for (const auto& [output, column] : spec.outputs) selected.push_back(output);
  }
  if (selected.empty()) return (*what = "no outputs mapped to columns", false);
  e->wrapped_outputs.assign(info.outputs.size(), false);
  for (const std::string& output : spec.wrapped_outputs) {
    const int index = info.OutputIndex(output);
    if (index >= 0) e->wrapped_outputs[index] = true;
  }
  for (const std::string& output : selected) {
    int index = info.OutputIndex(output);
    if (index < 0) {
      *what = "unknown output '" + output + "' (model " + info.name + " has " +
              JoinNames(info.outputs) + ")";
      return false;
    }
    auto mapped = spec.outputs.find(output);
    if (mapped == spec.outputs.end())
      return (*what = "output '" + output + "' is not mapped to a column", false);
    int column = trajectory.Find(mapped->second);
    if (column < 0)
      return (*what = "no column '" + mapped->second + "' for output '" + output + "'", false);
    auto weight = spec.output_weights.find(output);
    OutputChannel oc{index, weight == spec.output_weights.end() ? 1.0 : weight->second, nullptr};
    if (!OutputChannelOf(record_channels, column, info, index, e->Wrapped(index),
                         spec.IsDegreeColumn(trajectory.names[column]), window.t0, window.t_end,
                         &oc.channel, what)) {
      return false;
    }
    if (oc.channel->t.empty())
      return (*what = "column '" + mapped->second + "' has no samples", false);
    channels->push_back(std::move(oc));
  }
  return true;
}

// The nodes (t0 and every output sample time inside the window) and the samples grouped by
// node, weighted (normalised by the record's length if asked), each weighted value checked
// against overflow.
bool PlaceSamples(const ExperimentSpec& spec, const ModelInfo& info,
                  const ExperimentOptions& options, const Window& window,
                  const std::vector<OutputChannel>& channels, Experiment* e, std::string* what) {
  // One output's sample times are in order.
  std::vector<double> times{window.t0};
  for (const OutputChannel& oc : channels) {
    const auto [first, last] = InWindow(oc.channel->t, window.t0, window.t_end);
    times.insert(times.end(), oc.channel->t.begin() + first, oc.channel->t.begin() + last);
  }
  if (!std::is_sorted(times.begin(), times.end())) std::sort(times.begin(), times.end());
  for (double t : times) {
    if (e->node_time.empty() || t - e->node_time.back() > kNodeTimeTolerance)
      e->node_time.push_back(t);
  }
  const int nodes = e->num_nodes();
  if (nodes < 2) return (*what = "fewer than two sample times in the window", false);
  std::vector<std::vector<ExperimentSample>> by_node(nodes);
  e->output_sample_count.assign(info.outputs.size(), 0);
  e->channel_weight.assign(info.outputs.size(), 1.0);
  e->channel_noise_power.assign(info.outputs.size(), 0.0);
  for (const OutputChannel& oc : channels) {
    size_t k = 0;
    const auto [first, last] = InWindow(oc.channel->t, window.t0, window.t_end);
    for (size_t i = first; i < last; ++i) {
      const double t = oc.channel->t[i];
      while (e->node_time[k] < t - kNodeTimeTolerance) ++k;
      by_node[k].push_back({oc.output, oc.channel->value[i], oc.weight});
      ++e->output_sample_count[oc.output];
    }
    e->channel_weight[oc.output] = oc.weight;
  }
  for (int k = 0; k < nodes; ++k) {
    e->node_first_sample.push_back(e->num_samples());
    e->samples.insert(e->samples.end(), by_node[k].begin(), by_node[k].end());
  }
  e->node_first_sample.push_back(e->num_samples());
  if (options.normalize_by_length) {
    const double scale = 1.0 / std::sqrt(static_cast<double>(e->num_samples()));
    for (ExperimentSample& s : e->samples) s.weight *= scale;
  }
  for (const ExperimentSample& s : e->samples) {
    // A weighted residual this large squares to an overflowing cost.
    if (std::abs(s.weight * s.value) <= kMaxDataMagnitude && s.weight <= kMaxDataMagnitude) {
      continue;
    }
    const std::string& output = info.outputs[s.output];
    const auto weight = spec.output_weights.find(output);
    char text[300];
    std::snprintf(text, sizeof(text),
                  "weights.%s = %g makes the cost overflow: weight x measurement (%g) must "
                  "stay below 1e100",
                  output.c_str(), weight == spec.output_weights.end() ? 1.0 : weight->second,
                  s.weight * s.value);
    return (*what = text, false);
  }
  return true;
}

// Equal RK4 steps of at most the step bound (options.max_step, else the median interval) per
// interval, counted in double before anything is allocated for them (and before a count
// overflows int), within the step and memory limits; each step's start and midpoint (right
// limits) and end (left limit) times, then the last node.
bool PlanSteps(const ExperimentOptions& options, Experiment* e, std::vector<double>* right_times,
               std::vector<double>* end_times, std::string* what) {
  const int nodes = e->num_nodes();
  std::vector<double> intervals;
  for (int k = 0; k + 1 < nodes; ++k) intervals.push_back(e->node_time[k + 1] - e->node_time[k]);
  const double max_step = StepBound(intervals, options.max_step);
  std::vector<double> substeps;
  double total_steps = 0.0;
  for (double interval : intervals) {
    substeps.push_back(StepsIn(interval, max_step));
    total_steps += substeps.back();
  }
  if (!(total_steps <= static_cast<double>(options.max_steps))) {
    char text[300];
    std::snprintf(text, sizeof(text),
                  "%.3g s in steps of at most %.3g s is %.3g integration steps, more than the "
                  "limit of %.3g (limits.integration_steps; the step is integration.max_step, "
                  "else the median sample interval)",
                  e->node_time.back() - e->node_time.front(), max_step, total_steps,
                  static_cast<double>(options.max_steps));
    return (*what = text, false);
  }
  const double step_bytes = IntegrationStepBytes(total_steps, e->num_inputs);
  if (step_bytes > static_cast<double>(MemoryBudget())) {
    char text[120];
    std::snprintf(text, sizeof(text),
                  "%.3g integration steps (the step is integration.max_step, "
                  "else the median sample interval)",
                  total_steps);
    return (*what = OverBudget(text, step_bytes), false);
  }
  for (int k = 0; k + 1 < nodes; ++k) {
    const int m = static_cast<int>(substeps[k]);
    double h = intervals[k] / m;
    e->node_substeps.push_back(m);
    e->node_step.push_back(h);
    for (int s = 0; s < m; ++s) {
      right_times->push_back(e->node_time[k] + s * h);
      right_times->push_back(e->node_time[k] + (s + 0.5) * h);
      end_times->push_back(s + 1 == m ? e->node_time[k + 1] : e->node_time[k] + (s + 1) * h);
    }
  }
  right_times->push_back(e->node_time.back());
  return true;
}

// The input cache: every input at each step's start, midpoint and end (its interpolation, or
// its latent fit where the input has a noise model), then at the last node; an absent
// optional input is NaN throughout.
bool CacheInputs(const ExperimentSpec& spec, RecordChannels* record_channels,
                 const ModelInfo& info, const Window& window,
                 const std::vector<double>& right_times, const std::vector<double>& end_times,
                 Experiment* e, std::string* what) {
  const Trajectory& trajectory = record_channels->trajectory();
  const size_t steps = end_times.size();
  const int nu = e->num_inputs;
  e->input_cache.assign((3 * steps + 1) * nu, 0.0);
  for (int i = 0; i < nu; ++i) {
    const std::string& input = info.inputs[i];
    auto mapped = spec.inputs.find(input);
    if (mapped == spec.inputs.end() && info.InputOptional(i)) {
      for (size_t j = 0; j < 3 * steps + 1; ++j) {
        e->input_cache[j * nu + i] = std::numeric_limits<double>::quiet_NaN();
      }
      continue;
    }
    if (mapped == spec.inputs.end())
      return (*what = "input '" + input + "' is not mapped to a column", false);
    int column = trajectory.Find(mapped->second);
    if (column < 0)
      return (*what = "no column '" + mapped->second + "' for input '" + input + "'", false);
    const Channel& channel = record_channels->Extracted(column);
    if (channel.t.empty())
      return (*what = "input column '" + mapped->second + "' has no samples", false);
    for (size_t k = 0; k < channel.t.size() && info.InputPositive(i); ++k) {
      if (channel.value[k] > 0.0) continue;
      char text[64];
      std::snprintf(text, sizeof(text), "%g at t = %g s", channel.value[k], channel.t[k]);
      *what = "input '" + input + "' (column '" + mapped->second + "') is " + text +
              ": the model needs it > 0";
      return false;
    }
    auto method = spec.interpolation.find(input);
    Interpolation interpolation =
        method == spec.interpolation.end() ? spec.default_interpolation : method->second;
    std::vector<double> right, end;
    auto noise = spec.input_noise.find(input);
    if (noise == spec.input_noise.end()) {
      right = InterpolateAt(channel, interpolation, right_times);
      end = InterpolateAt(channel, interpolation, end_times, true);
    } else if (!FitLatentInput(spec, input, mapped->second, i, channel, window.t0, window.t_end,
                               right_times, end_times, e, &right, &end, what)) {
      const std::string& key = noise->second.key;
      *what = "input '" + input + "': " + (key.empty() ? "" : key + ": ") + *what;
      return false;
    }
    for (size_t j = 0; j < steps; ++j) {
      e->input_cache[(3 * j) * nu + i] = right[2 * j];
      e->input_cache[(3 * j + 1) * nu + i] = right[2 * j + 1];
      e->input_cache[(3 * j + 2) * nu + i] = end[j];
    }
    e->input_cache[(3 * steps) * nu + i] = right.back();
  }
  return true;
}

// Initial state: every mapped output's value (linear interpolation) and rate at t0; the
// same-named outputs as defaults, the model's guess over them for start values (with each
// guess's standard error: the start fits' errors propagated one at a time), given values over
// both.
bool StartStates(const ExperimentSpec& spec, RecordChannels* record_channels,
                 const ModelInfo& info, const ExperimentOptions& options, const Window& window,
                 Experiment* e, std::string* what) {
  const Trajectory& trajectory = record_channels->trajectory();
  const size_t ny = info.outputs.size();
  std::vector<double> y0(ny, std::numeric_limits<double>::quiet_NaN()), ydot0 = y0;
  std::vector<double> y0_sigma(ny, 0.0), ydot0_sigma(ny, 0.0);
  for (const auto& [output, column_name] : spec.outputs) {
    const int o = info.OutputIndex(output);
    const int column = trajectory.Find(column_name);
    if (o < 0 || column < 0) continue;
    const Channel* extracted = nullptr;
    if (!OutputChannelOf(record_channels, column, info, o, e->Wrapped(o),
                         spec.IsDegreeColumn(column_name), window.t0, window.t_end, &extracted,
                         what)) {
      return false;
    }
    const Channel& channel = *extracted;
    if (channel.t.empty()) continue;
    y0[o] = InterpolateAt(channel, Interpolation::kLinear, {window.t0})[0];
    const bool angle = o < static_cast<int>(info.angle_outputs.size()) && info.angle_outputs[o];
    StartFit fit;
    if (FitStart(channel, window.t0, options.rate_window, angle, &fit)) {
      ydot0[o] = fit.rate;
      y0_sigma[o] = fit.value_sigma;
      ydot0_sigma[o] = fit.rate_sigma;
    }
  }
  // x(y0, ydot0): same-named outputs, then the model's guess over them.
  auto guess = [&](const std::vector<double>& y, const std::vector<double>& ydot) {
    std::vector<double> x(info.states.size(), 0.0);
    for (size_t s = 0; s < info.states.size(); ++s) {
      const int o = info.OutputIndex(info.states[s]);
      if (o >= 0 && std::isfinite(y[o])) x[s] = y[o];
    }
    if (options.state_guess) options.state_guess(y.data(), ydot.data(), x.data());
    return x;
  };
  e->initial_state.assign(info.states.size(), 0.0);
  for (size_t s = 0; s < info.states.size(); ++s) {
    const int o = info.OutputIndex(info.states[s]);
    if (o >= 0 && std::isfinite(y0[o])) e->initial_state[s] = y0[o];
  }
  e->initial_state_guess = guess(y0, ydot0);
  std::vector<double> variance(info.states.size(), 0.0);
  bool known = true;
  for (size_t o = 0; o < ny; ++o) {
    for (auto [values, sigma] : {std::pair{&y0, &y0_sigma}, std::pair{&ydot0, &ydot0_sigma}}) {
      if (!std::isfinite((*values)[o]) || (*sigma)[o] == 0.0) continue;
      known &= std::isfinite((*sigma)[o]);
      if (!known) break;
      std::vector<double> y = y0, ydot = ydot0;
      (values == &y0 ? y : ydot)[o] += (*sigma)[o];
      const std::vector<double> moved = guess(y, ydot);
      for (size_t s = 0; s < moved.size(); ++s) {
        const double d = moved[s] - e->initial_state_guess[s];
        if (std::isfinite(d)) variance[s] += d * d;
      }
    }
  }
  e->initial_state_sigma.assign(info.states.size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t s = 0; s < info.states.size() && known; ++s) {
    if (variance[s] > 0.0) e->initial_state_sigma[s] = std::sqrt(variance[s]);
  }
  for (size_t s = 0; s < info.states.size(); ++s) {
    auto given = spec.initial_state.find(info.states[s]);
    if (given == spec.initial_state.end()) continue;
    e->initial_state[s] = given->second;
    e->initial_state_guess[s] = given->second;
    e->initial_state_sigma[s] = std::numeric_limits<double>::quiet_NaN();
  }
  return true;
}

// Prior weight: the outputs' weighted noise level (second differences of the samples).
void SetPriorWeight(const ExperimentOptions& options, const Window& window,
                    const std::vector<OutputChannel>& channels, Experiment* e) {
  double noise2 = 0.0;
  int counted = 0;
  for (const OutputChannel& oc : channels) {
    NoiseLevel level;
    const auto [first, last] = InWindow(oc.channel->t, window.t0, window.t_end);
    // A wrapped angle's second differences jump by a turn where it wraps (a spiral's heading:
    // 0.42 rad instead of its 0.0037 rad of noise), so they are taken modulo one.
    const bool wrapped = e->Wrapped(oc.output);
    for (size_t i = first; i < last; ++i) {
      level.Add(oc.channel->value[i], [wrapped](double d) { return wrapped ? WrapAngle(d) : d; });
    }
    const double sigma = level.Sigma();
    if (!std::isfinite(sigma)) continue;
    e->channel_noise_power[oc.output] = level.count() * sigma * sigma;
    noise2 += level.count() * (oc.weight * sigma) * (oc.weight * sigma);
    counted += level.count();
  }
  if (counted > 0) {
    e->prior_weight = std::sqrt(noise2 / counted);
    if (options.normalize_by_length)
      e->prior_weight /= std::sqrt(static_cast<double>(e->num_samples()));
  }
}

}  // namespace

bool BuildExperiment(const ExperimentSpec& spec, const Trajectory& trajectory,
                     const ModelInfo& info, const ExperimentOptions& options,
                     Experiment* experiment, std::string* error) {
  RecordChannels channels(trajectory);
  return BuildExperiment(spec, &channels, info, options, experiment, error);
}

bool BuildExperiment(const ExperimentSpec& spec, RecordChannels* record_channels,
                     const ModelInfo& info, const ExperimentOptions& options,
                     Experiment* experiment, std::string* error) {
  const Trajectory& trajectory = record_channels->trajectory();
  Experiment e;
  e.name = spec.name;
  e.num_inputs = static_cast<int>(info.inputs.size());
  const Window window{std::max(spec.t_begin, trajectory.t.front()),
                      std::min(spec.t_end, trajectory.t.back())};
  std::vector<OutputChannel> channels;
  std::vector<double> right_times, end_times;
  std::string what;
  const bool built =
      (window.t_end > window.t0 || (what = "empty time window", false)) &&
      SelectOutputs(spec, record_channels, info, options, window, &e, &channels, &what) &&
      PlaceSamples(spec, info, options, window, channels, &e, &what) &&
      PlanSteps(options, &e, &right_times, &end_times, &what) &&
      CacheInputs(spec, record_channels, info, window, right_times, end_times, &e, &what) &&
      StartStates(spec, record_channels, info, options, window, &e, &what);
  if (!built) {
    *error = "experiment '" + spec.name + "' (" + trajectory.source + "): " + what;
    return false;
  }
  SetPriorWeight(options, window, channels, &e);
  *experiment = std::move(e);
  return true;
}

}  // namespace vesselid

#include "problems/nomoto/closed_loop_simulator.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace vesselid::nomoto {

bool ClosedLoopOptions::IsValid(std::string* error) const {
  const Excitation& e = excitation;
  if (!(steering_time_constant > 0))
    *error = "steering gear Tm must be > 0";
  else if (!(controller_gain > 0))
    *error = "controller gain kp must be > 0";
  else if (!(rudder_limit > 0))
    *error = "rudder limit must be > 0";
  else if (!(sample_time > 0))
    *error = "sample_time must be > 0";
  else if (substeps < 1)
    *error = "substeps must be >= 1";
  else if (!(duration > sample_time))
    *error = "duration must exceed sample_time";
  else if (!(rudder_noise >= 0) || !(heading_noise >= 0) || !(heading_resolution >= 0))
    *error = "noise levels must be >= 0";
  else if (!(rudder_rate >= 0))
    *error = "rudder rate limit must be >= 0";
  else if (!std::isfinite(rudder_bias) || !std::isfinite(disturbance_amplitude))
    *error = "rudder bias and disturbance must be finite";
  else if (disturbance_amplitude != 0 && !(disturbance_period > 0))
    *error = "a disturbance needs a period > 0";
  else if (!(speed >= 0) || !std::isfinite(speed))
    *error = "speed must be >= 0";
  else if (e.type == Excitation::Type::kPlanned &&
           (e.planned_t.size() < 2 || e.planned_t.size() != e.planned_delta.size()))
    *error = "a planned excitation needs at least two command samples";
  else if (e.type != Excitation::Type::kZigzag && e.type != Excitation::Type::kPlanned &&
           e.periods.empty())
    *error = "excitation needs a period";
  else if (e.type == Excitation::Type::kSine && e.periods.size() != 1)
    *error = "a sine has one period";
  else if (std::any_of(e.periods.begin(), e.periods.end(), [](double p) { return !(p > 0); }))
    *error = "excitation periods must be > 0";
  else if (e.type == Excitation::Type::kZigzag &&
           (!(e.zigzag_rudder > 0) || !(e.zigzag_heading > 0)))
    *error = "zigzag needs rudder and heading angles > 0";
  else
    return true;
  return false;
}

namespace {

// The planned command at t: linear between samples, held beyond them.
double PlannedCommand(const Excitation& e, double t) {
  const auto after = std::upper_bound(e.planned_t.begin(), e.planned_t.end(), t);
  if (after == e.planned_t.begin()) return e.planned_delta.front();
  if (after == e.planned_t.end()) return e.planned_delta.back();
  const size_t k = static_cast<size_t>(after - e.planned_t.begin());
  const double w = (t - e.planned_t[k - 1]) / (e.planned_t[k] - e.planned_t[k - 1]);
  return (1.0 - w) * e.planned_delta[k - 1] + w * e.planned_delta[k];
}

double HeadingSetpoint(const Excitation& e, double t) {
  if (e.type == Excitation::Type::kSine) return e.amplitude * std::sin(2 * M_PI * t / e.periods[0]);
  // Schroeder phases keep the multi-sine's crest factor low.
  const size_t n = e.periods.size();
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double phase = -M_PI * static_cast<double>(i * (i + 1)) / static_cast<double>(n);
    sum += std::sin(2 * M_PI * t / e.periods[i] + phase);
  }
  return e.amplitude * std::sqrt(2.0 / static_cast<double>(n)) * sum;
}

}  // namespace

bool SimulateClosedLoop(const ModelHandle& model, const std::vector<double>& parameters,
                        const ClosedLoopOptions& options, Trajectory* trajectory,
                        std::string* error) {
  if (!options.IsValid(error)) return false;
  const ModelInfo& info = model.info();
  const int n = static_cast<int>(info.states.size());
  const int psi_out = info.OutputIndex("psi"), r_out = info.OutputIndex("r");
  int gain = -1;
  for (const char* name : {"K", "K_nd", "b"}) {
    if (gain < 0) gain = info.ParameterIndex(name);
  }
  const int speed_input = info.InputIndex("U");
  if (info.inputs.size() != (speed_input < 0 ? 1u : 2u) || info.InputIndex("delta") != 0 ||
      psi_out < 0 || r_out < 0 || gain < 0) {
    *error = "model " + info.name +
             " is not a steering model (inputs delta and optionally U, outputs psi, r, a gain)";
    return false;
  }
  if ((speed_input >= 0) != (options.speed > 0)) {
    *error = speed_input >= 0 ? "model " + info.name + " takes a speed: the run needs a speed > 0"
                              : "model " + info.name + " takes no speed input";
    return false;
  }
  const double sign_k = parameters[gain] < 0 ? -1.0 : 1.0;
  const Excitation& e = options.excitation;
  const bool zigzag = e.type == Excitation::Type::kZigzag;
  double zigzag_command = sign_k * e.zigzag_first * e.zigzag_rudder;
  std::mt19937_64 random(options.seed);
  std::mt19937_64 phase_random(options.seed + 7919);  // keeps the noise of older configs
  const double disturbance_phase =
      std::uniform_real_distribution<double>(0, 2 * M_PI)(phase_random);

  // Closed-loop state z = [model states, delta]. The model steers on
  // u = [delta + bias + disturbance(t) (, U)].
  std::vector<double> y(info.outputs.size()), u(info.inputs.size(), options.speed);
  auto inputs = [&](const std::vector<double>& z, double t) {
    u[0] = z[n] + options.rudder_bias;
    if (options.disturbance_amplitude != 0) {
      u[0] += options.disturbance_amplitude *
              std::sin(2 * M_PI * t / options.disturbance_period + disturbance_phase);
    }
    return u.data();
  };
  auto heading = [&](const std::vector<double>& z, double t) {
    model.Output(z.data(), inputs(z, t), parameters.data(), y.data());
    return y[psi_out];
  };
  auto delta_set = [&](const std::vector<double>& z, double t) {
    double set = zigzag ? zigzag_command
                 : e.type == Excitation::Type::kPlanned
                     ? PlannedCommand(e, t)
                     : sign_k * options.controller_gain * (HeadingSetpoint(e, t) - heading(z, t));
    return std::clamp(set, -options.rudder_limit, options.rudder_limit);
  };
  auto rhs = [&](const std::vector<double>& z, double t, std::vector<double>* zdot) {
    if (!model.Derivative(z.data(), inputs(z, t), parameters.data(), zdot->data())) return false;
    double rate = (delta_set(z, t) - z[n]) / options.steering_time_constant;
    if (options.rudder_rate > 0) rate = std::clamp(rate, -options.rudder_rate, options.rudder_rate);
    (*zdot)[n] = rate;
    return true;
  };

  const long samples =
      static_cast<long>(std::floor(options.duration / options.sample_time + 1e-9)) + 1;
  Trajectory out;
  out.names = {"psi_set", "delta_set", "delta", "psi", "r", "delta_true", "psi_true"};
  if (speed_input >= 0) out.names.push_back("U");
  out.columns.assign(out.names.size(), {});
  for (auto& column : out.columns) column.reserve(samples);
  out.t.reserve(samples);
  std::normal_distribution<double> rudder_noise(0.0, options.rudder_noise);
  std::normal_distribution<double> heading_noise(0.0, options.heading_noise);

  std::vector<double> z(n + 1, 0.0), k1(n + 1), k2(n + 1), k3(n + 1), k4(n + 1), zs(n + 1);
  const double h = options.sample_time / options.substeps;
  for (long k = 0; k < samples; ++k) {
    const double t = k * options.sample_time;
    const double psi = heading(z, t);
    if (zigzag) {
      // sign_k * command > 0 turns the heading up (r' ~ K delta): reversed when the heading
      // reaches +psi_z; the other way at -psi_z. (The heading itself is not scaled by the sign
      // of K: a ship with K < 0 never reversed its first rudder before.)
      if (psi >= e.zigzag_heading && sign_k * zigzag_command > 0)
        zigzag_command = -zigzag_command;
      if (psi <= -e.zigzag_heading && sign_k * zigzag_command < 0)
        zigzag_command = -zigzag_command;
    }
    out.t.push_back(t);
    out.columns[0].push_back(zigzag ? std::nan("") : HeadingSetpoint(e, t));
    out.columns[1].push_back(delta_set(z, t));
    out.columns[2].push_back(z[n] + (options.rudder_noise > 0 ? rudder_noise(random) : 0.0));
    double logged = psi + (options.heading_noise > 0 ? heading_noise(random) : 0.0);
    if (options.heading_resolution > 0) {
      logged = options.heading_resolution * std::round(logged / options.heading_resolution);
    }
    out.columns[3].push_back(logged);
    out.columns[4].push_back(y[r_out]);
    out.columns[5].push_back(z[n]);
    out.columns[6].push_back(psi);
    if (speed_input >= 0) out.columns[7].push_back(options.speed);
    if (k + 1 == samples) break;
    for (int s = 0; s < options.substeps; ++s) {
      const double ts = t + s * h;
      bool ok = rhs(z, ts, &k1);
      for (int i = 0; i <= n; ++i) zs[i] = z[i] + 0.5 * h * k1[i];
      ok = ok && rhs(zs, ts + 0.5 * h, &k2);
      for (int i = 0; i <= n; ++i) zs[i] = z[i] + 0.5 * h * k2[i];
      ok = ok && rhs(zs, ts + 0.5 * h, &k3);
      for (int i = 0; i <= n; ++i) zs[i] = z[i] + h * k3[i];
      ok = ok && rhs(zs, ts + h, &k4);
      if (!ok) {
        *error = "closed-loop simulation diverged at t = " + std::to_string(ts);
        return false;
      }
      for (int i = 0; i <= n; ++i) z[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
  }
  *trajectory = std::move(out);
  return true;
}

}  // namespace vesselid::nomoto

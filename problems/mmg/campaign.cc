#include "problems/mmg/campaign.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace vesselid::mmg {

bool CampaignRun::IsValid(std::string* error) const {
  if (!(rudder > 0) || rudder > 0.7)
    *error = "rudder must be in (0, 40] deg";
  else if (type == Type::kZigzag && !(heading > 0))
    *error = "a zigzag needs a heading change > 0";
  else if (!(duration > sample_time))
    *error = "duration must exceed sample_time";
  else if (!(propeller_rate > 0) || !std::isfinite(propeller_rate))
    *error = "propeller_rate must be > 0 [1/s]";
  else if (!std::isfinite(rudder_bias) || !std::isfinite(disturbance_amplitude))
    *error = "rudder bias and disturbance must be finite";
  else if (disturbance_amplitude != 0 && !(disturbance_period > 0))
    *error = "a disturbance needs a period > 0";
  else if (!(position_noise >= 0) || !(heading_noise >= 0) || !(speed_noise >= 0) ||
           !(rudder_noise >= 0))
    *error = "noise levels must be >= 0";
  else if (!(sample_time > 0) || substeps < 1)
    *error = "sample_time must be > 0 and substeps >= 1";
  else if (!(steering_time_constant > 0) || !(rudder_rate >= 0))
    *error = "steering gear Tm must be > 0 and its rate limit >= 0";
  else
    return true;
  return false;
}

bool SelfPropulsionSpeed(const ModelHandle& model, const double* parameters, double n,
                         double* speed) {
  auto surge = [&](double u) {
    const double x[6] = {0, 0, 0, u, 0, 0}, in[2] = {0.0, n};
    double xdot[6];
    return model.Derivative(x, in, parameters, xdot) ? xdot[3] : std::nan("");
  };
  double low = 1e-3, high = 20.0;
  if (!(surge(low) > 0) || !(surge(high) < 0)) return false;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (low + high);
    (surge(mid) > 0 ? low : high) = mid;
  }
  *speed = 0.5 * (low + high);
  return true;
}

bool SimulateRun(const ModelHandle& model, const std::vector<double>& parameters,
                 const CampaignRun& run, Trajectory* trajectory, std::string* error) {
  if (!run.IsValid(error)) return false;
  const ModelInfo& info = model.info();
  if (info.states.size() != 6 || info.inputs.size() != 2 || info.InputIndex("n") != 1) {
    *error = "model " + info.name + " is not a 3-DOF manoeuvring model (inputs delta, n)";
    return false;
  }
  double u0 = 0.0;
  if (!SelfPropulsionSpeed(model, parameters.data(), run.propeller_rate, &u0)) {
    *error = "no straight-course speed balances the forces at n = " +
             std::to_string(run.propeller_rate) + " 1/s";
    return false;
  }
  std::mt19937_64 random(run.seed);
  const double phase = std::uniform_real_distribution<double>(0, 2 * M_PI)(random);
  double command = run.first * run.rudder;

  // z = [x, y, psi, u, v, r, delta]; the ship steers on delta + bias + disturbance(t).
  using State = std::array<double, 7>;
  auto rhs = [&](const State& z, double t, State* zdot) {
    double in[2] = {z[6] + run.rudder_bias, run.propeller_rate};
    if (run.disturbance_amplitude != 0) {
      in[0] += run.disturbance_amplitude * std::sin(2 * M_PI * t / run.disturbance_period + phase);
    }
    if (!model.Derivative(z.data(), in, parameters.data(), zdot->data())) return false;
    double rate = (command - z[6]) / run.steering_time_constant;
    if (run.rudder_rate > 0) rate = std::clamp(rate, -run.rudder_rate, run.rudder_rate);
    (*zdot)[6] = rate;
    return true;
  };
  const long samples = static_cast<long>(std::floor(run.duration / run.sample_time + 1e-9)) + 1;
  Trajectory out;
  out.names = {"x",      "y",      "psi",    "U",          "delta",   "n",
               "u_true", "v_true", "r_true", "delta_true", "psi_true"};
  out.columns.assign(out.names.size(), {});
  std::normal_distribution<double> normal(0.0, 1.0);
  State z = {0, 0, 0, u0, 0, 0, 0}, k1, k2, k3, k4, zs;
  const double h = run.sample_time / run.substeps;
  for (long k = 0; k < samples; ++k) {
    const double t = k * run.sample_time;
    if (run.type == CampaignRun::Type::kZigzag) {
      if (z[2] >= run.heading && command > 0) command = -run.rudder;
      if (z[2] <= -run.heading && command < 0) command = run.rudder;
    }
    out.t.push_back(t);
    const double logged[] = {z[0] + run.position_noise * normal(random),
                             z[1] + run.position_noise * normal(random),
                             z[2] + run.heading_noise * normal(random),
                             std::hypot(z[3], z[4]) + run.speed_noise * normal(random),
                             z[6] + run.rudder_noise * normal(random),
                             run.propeller_rate,
                             z[3],
                             z[4],
                             z[5],
                             z[6],
                             z[2]};
    for (size_t c = 0; c < out.names.size(); ++c) out.columns[c].push_back(logged[c]);
    if (k + 1 == samples) break;
    for (int s = 0; s < run.substeps; ++s) {
      const double ts = t + s * h;
      bool ok = rhs(z, ts, &k1);
      for (int i = 0; i < 7; ++i) zs[i] = z[i] + 0.5 * h * k1[i];
      ok = ok && rhs(zs, ts + 0.5 * h, &k2);
      for (int i = 0; i < 7; ++i) zs[i] = z[i] + 0.5 * h * k2[i];
      ok = ok && rhs(zs, ts + 0.5 * h, &k3);
      for (int i = 0; i < 7; ++i) zs[i] = z[i] + h * k3[i];
      ok = ok && rhs(zs, ts + h, &k4);
      if (!ok) {
        *error = "simulation left the model's domain at t = " + std::to_string(ts) + " s";
        return false;
      }
      for (int i = 0; i < 7; ++i) z[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
  }
  *trajectory = std::move(out);
  return true;
}

}  // namespace vesselid::mmg

// Data of the lumped input-gain model itself (tests): PWM mean and difference commands held
// for random 2-6 s at 10 Hz, the model integrated by RK4, GNSS n, e at 5 Hz, AHRS heading at
// 50 Hz with noise. Inputs change only on the 0.1 s PWM grid, so the regression grid's
// zero-order hold is exact.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/model/experiment.h"
#include "engine/model/model_handle.h"
#include "engine/solve/parameter.h"
#include "problems/input_gain/input_gain_model.h"

namespace vesselid::testing {

struct LumpedRun {
  double duration = 40.0;
  double position_noise = 0.0;  // m
  double heading_noise = 0.0;   // rad
  unsigned seed = 1;
  std::vector<double> x0;  // initial state; empty: moving ahead at 0.8 m/s
};

// States and inputs on the 0.1 s command grid (where inputs may change).
struct LumpedGrid {
  std::vector<double> t;
  std::vector<std::vector<double>> x, u;
};

inline Trajectory SimulateLumped(const ModelHandle& model, const std::vector<double>& p,
                                 const LumpedRun& run, LumpedGrid* grid = nullptr) {
  const int nx = static_cast<int>(model.info().states.size());
  std::mt19937 random(run.seed);
  std::uniform_real_distribution<double> mean(0.15, 0.9), difference(-0.5, 0.5), hold(2.0, 6.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> x = run.x0;
  if (x.empty()) {
    x.assign(nx, 0.0);
    x[3] = 0.8;
  }
  Trajectory data;
  data.source = "lumped";
  data.names = {"n", "e", "heading", "pwm_L", "pwm_R"};
  data.columns.resize(5);
  const double kNaN = std::numeric_limits<double>::quiet_NaN();
  const double h = 0.01;
  double u_m = mean(random), u_d = difference(random), next_change = hold(random);
  double pwm[2] = {std::clamp(u_m + u_d, -1.0, 1.0), std::clamp(u_m - u_d, -1.0, 1.0)};
  if (nx == 8 && run.x0.empty()) {
    // Dynamic propellers start at steady state: T_i' = (T_s - T_i) / tau_T is affine in T_i,
    // so two evaluations give its root whatever the thrust law.
    std::vector<double> at0 = x, at1 = x, d0(nx), d1(nx);
    at1[6] = at1[7] = 1.0;
    model.Derivative(at0.data(), pwm, p.data(), d0.data());
    model.Derivative(at1.data(), pwm, p.data(), d1.data());
    for (int i = 6; i < 8; ++i) x[i] = d0[i] / (d0[i] - d1[i]);
  }
  const int steps = static_cast<int>(std::lround(run.duration / h));
  std::vector<double> k1(nx), k2(nx), k3(nx), k4(nx), xs(nx);
  for (int k = 0; k <= steps; ++k) {
    const double t = k * h;
    if (k % 10 == 0 && t >= next_change) {  // new command on the PWM grid
      u_m = mean(random);
      u_d = difference(random);
      next_change = t + hold(random);
    }
    if (k % 10 == 0) {
      pwm[0] = std::clamp(u_m + u_d, -1.0, 1.0);
      pwm[1] = std::clamp(u_m - u_d, -1.0, 1.0);
      if (grid != nullptr) {
        grid->t.push_back(t);
        grid->x.push_back(x);
        grid->u.push_back({pwm[0], pwm[1]});
      }
    }
    if (k % 2 == 0) {  // a row every 0.02 s: heading always, PWM every 0.1 s, GNSS 0.2 s
      data.t.push_back(t);
      const bool gnss = k % 20 == 0, command = k % 10 == 0;
      data.columns[0].push_back(gnss ? x[0] + run.position_noise * gauss(random) : kNaN);
      data.columns[1].push_back(gnss ? x[1] + run.position_noise * gauss(random) : kNaN);
      data.columns[2].push_back(WrapAngle(x[2] + run.heading_noise * gauss(random)));
      data.columns[3].push_back(command ? pwm[0] : kNaN);
      data.columns[4].push_back(command ? pwm[1] : kNaN);
    }
    model.Derivative(x.data(), pwm, p.data(), k1.data());
    for (int i = 0; i < nx; ++i) xs[i] = x[i] + 0.5 * h * k1[i];
    model.Derivative(xs.data(), pwm, p.data(), k2.data());
    for (int i = 0; i < nx; ++i) xs[i] = x[i] + 0.5 * h * k2[i];
    model.Derivative(xs.data(), pwm, p.data(), k3.data());
    for (int i = 0; i < nx; ++i) xs[i] = x[i] + h * k3[i];
    model.Derivative(xs.data(), pwm, p.data(), k4.data());
    for (int i = 0; i < nx; ++i) x[i] += h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  }
  return data;
}

// A lumped catamaran close to what the campaign identifies (parameter order of the default
// bases; tau_T appended for the dynamic variant).
inline std::vector<double> LumpedTruth(bool dynamic) {
  std::vector<double> p = {0.01, -0.2, -0.25, 0.9, 0.0,          // u: 1 u |u|u vr rr
                           0.002, -0.6, -0.08, -1.2, -0.7, 0.03,  // v: 1 v r |v|v ur uv
                           0.0004, 0.3, -0.36, -0.25, -0.01, 0.17,  // r: 1 v r |r|r uv ur
                           0.33, 0.06, 0.45,                        // b_u b_v b_r
                           1.2, 0.6, 0.5, 0.0, 0.0};                // k_f k_r1 k_r2 d_f d_r
  if (dynamic) p.push_back(0.25);
  return p;
}

// The same craft with another thrust law: the law's parameters of LumpedTruth's, in the
// model's order (thrust_law.h).
inline std::vector<double> LumpedTruth(bool dynamic, const input_gain::ThrustLaw& law) {
  std::vector<double> p = LumpedTruth(dynamic);
  p.resize(20);  // the bases and the gains
  const input_gain::ThrustOffsets offsets(law, dynamic);
  const double values[] = {1.2, 0.6, 0.5, 0.0, 0.0, 0.25};
  const int at[] = {offsets.k_f, offsets.k_r1, offsets.k_r2,
                    offsets.d_f, offsets.d_r,  offsets.tau_T};
  for (int k = 0; k < 6; ++k) {
    if (at[k] >= 0) p.push_back(values[k]);
  }
  return p;
}

// Parameters started `perturbation` off the truth (alternating sign), with the dead zone held
// (it is not excited above zero thrust) and the propeller time constant bounded.
inline std::vector<ParameterSpec> LumpedSpecs(const ModelInfo& info,
                                              const std::vector<double>& truth,
                                              double perturbation) {
  std::vector<ParameterSpec> specs;
  for (size_t i = 0; i < truth.size(); ++i) {
    ParameterSpec s;
    s.name = info.parameters[i];
    s.start = truth[i] * (1.0 + (i % 2 == 0 ? perturbation : -perturbation));
    s.scale = std::max(std::abs(truth[i]), 0.01);
    if (s.name == "d_f" || s.name == "d_r") s.role = ParameterRole::kFixed;
    if (s.name == "tau_T") {
      s.lower = 0.02;
      s.upper = 2.0;
    }
    specs.push_back(s);
  }
  return specs;
}

inline ExperimentSpec LumpedSpec(const std::string& name) {
  ExperimentSpec spec;
  spec.name = name;
  spec.inputs = {{"u_L", "pwm_L"}, {"u_R", "pwm_R"}};
  spec.outputs = {{"n", "n"}, {"e", "e"}, {"psi", "heading"}};
  spec.default_interpolation = Interpolation::kZeroOrderHold;
  return spec;
}

}  // namespace vesselid::testing

// Synthetic data from the Eriksen-Breivik model itself (exact structure, no disturbance), for
// the model battery and the step-regression tests: a reference parameter vector and step
// sequences simulated with RK4 and logged like the craft campaign (columns run, n, e, course,
// sog, rot, throttle, rudder).
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "engine/data/trajectory.h"
#include "engine/model/model_handle.h"
#include "problems/eriksen2dof/eriksen_model.h"

namespace vesselid::testing {

// A planing craft in the model's own terms (speed_scale 10 m/s, yaw_rate_scale 0.5 rad/s,
// u = U / 10, v = r / 0.5): symmetric in yaw, inertia with a step near 5 m/s.
//   sigma_U = -0.02 + 0.5 u + 0.2 u^2 + 0.15 v^2       sigma_r = 0.8 v - 0.3 u v + 0.2 v^3
//   m_U = 0.25 + 0.05 u + 0.1 tanh(U - 5)             m_r = 2.0 + 0.5 u
inline std::vector<double> ReferenceCraft(const ModelInfo& info) {
  std::vector<double> p(info.parameters.size(), 0.0);
  auto set = [&](const std::string& name, double value) {
    p[info.ParameterIndex(name)] = value;
  };
  set("sigma_U.1", -0.02);
  set("sigma_U.U", 0.5);
  set("sigma_U.U2", 0.2);
  set("sigma_U.r2", 0.15);
  set("sigma_r.r", 0.8);
  set("sigma_r.Ur", -0.3);
  set("sigma_r.r3", 0.2);
  set("m_U.1", 0.25);
  set("m_U.U", 0.05);
  set("m_U.tanh", 0.1);
  set("m_r.1", 2.0);
  set("m_r.U", 0.5);
  set("m_U.a", 1.0);
  set("m_U.b", 5.0);
  set("m_r.a", 1.0);
  set("m_r.b", 5.0);
  return p;
}

struct Level {
  double duration, throttle, rudder;
};

// Seed 004's campaign in small: throttle 0 -> top -> 0 in `step` at each rudder setting, and
// rudder 0 -> 1 -> 0 at each throttle setting, each level held `hold` s.
inline std::vector<std::vector<Level>> StepCampaign(const std::vector<double>& rudders,
                                                    const std::vector<double>& throttles,
                                                    double top, double step, double hold) {
  std::vector<std::vector<Level>> runs;
  const int n = static_cast<int>(std::lround(top / step));
  for (double rudder : rudders) {
    std::vector<Level> run;
    for (int k = 0; k <= 2 * n; ++k) run.push_back({hold, step * (k <= n ? k : 2 * n - k), rudder});
    runs.push_back(run);
  }
  const int m = static_cast<int>(std::lround(1.0 / step));
  for (double throttle : throttles) {
    std::vector<Level> run;
    for (int k = 0; k <= 2 * m; ++k) run.push_back({hold, throttle, step * (k <= m ? k : 2 * m - k)});
    runs.push_back(run);
  }
  return runs;
}

// Simulates each run from its first level's steady state (reached by a 200 s run-in), logs
// every `period` s with Gaussian noise on sog and rot; runs follow each other in time.
inline Trajectory SimulateRuns(const ModelHandle& model, const std::vector<double>& p,
                               const std::vector<std::vector<Level>>& runs, double period,
                               double sog_noise, double rot_noise, unsigned seed) {
  Trajectory data;
  data.source = "eriksen_data";
  data.names = {"run", "n", "e", "course", "sog", "rot", "throttle", "rudder"};
  data.columns.resize(data.names.size());
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  const int substeps = 10;
  const double h = period / substeps;
  auto rk4 = [&](double* x, const double* u) {
    double k1[5], k2[5], k3[5], k4[5], y[5];
    model.Derivative(x, u, p.data(), k1);
    for (int i = 0; i < 5; ++i) y[i] = x[i] + 0.5 * h * k1[i];
    model.Derivative(y, u, p.data(), k2);
    for (int i = 0; i < 5; ++i) y[i] = x[i] + 0.5 * h * k2[i];
    model.Derivative(y, u, p.data(), k3);
    for (int i = 0; i < 5; ++i) y[i] = x[i] + h * k3[i];
    model.Derivative(y, u, p.data(), k4);
    for (int i = 0; i < 5; ++i) x[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  };
  double t = 0.0;
  for (size_t r = 0; r < runs.size(); ++r) {
    double x[5] = {0.0, 0.0, 0.0, 3.0, 0.0};
    const double first[2] = {runs[r][0].throttle, runs[r][0].rudder};
    for (int k = 0; k < 200 * substeps / period; ++k) rk4(x, first);
    x[0] = x[1] = x[2] = 0.0;
    for (const Level& level : runs[r]) {
      const double u[2] = {level.throttle, level.rudder};
      const int samples = static_cast<int>(std::lround(level.duration / period));
      for (int k = 0; k < samples; ++k) {
        const double row[8] = {static_cast<double>(r),
                               x[0],
                               x[1],
                               std::remainder(x[2], 2.0 * M_PI),
                               x[3] + sog_noise * normal(random),
                               x[4] + rot_noise * normal(random),
                               u[0],
                               u[1]};
        data.t.push_back(t);
        for (int c = 0; c < 8; ++c) data.columns[c].push_back(row[c]);
        for (int s = 0; s < substeps; ++s) rk4(x, u);
        t += period;
      }
    }
    t += 5.0;
  }
  return data;
}

}  // namespace vesselid::testing

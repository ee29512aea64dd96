// The filter-error method's filter run in double, for what a run reports: each sample's
// innovation and its variance (whiteness, the likelihood) and the k-step-ahead prediction
// through the filter (the model flown k nodes from the filtered state, the disturbance's mean
// carried: ar1 decayed by exp(-dt / tau), a bias held, a wave's mean left out).
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "engine/model/kalman_filter.h"

namespace vesselid {

struct FilterRun {
  std::vector<double> innovation;  // per sample: y - predicted (one step, before its update)
  std::vector<double> variance;    // per sample: S
  // Per sample: its output predicted from the filtered state `steps` nodes earlier (NaN for
  // the first `steps` nodes).
  std::vector<double> prediction;
  int steps = 0;
  // -log L = 1/2 sum (nu^2 / S + log S + log 2 pi)
  double negative_log_likelihood = 0.0;
};

template <class Model>
bool RunFilterInnovations(const Model& model, const Experiment& e, const double* p,
                          const double* x0, const double* p0, const DisturbanceLayout& layout,
                          const double* theta, int steps, FilterRun* run) {
  constexpr int n = Model::kNumStates;
  constexpr int ny = Model::kNumOutputs;
  const int samples = e.num_samples();
  run->innovation.assign(samples, std::numeric_limits<double>::quiet_NaN());
  run->variance.assign(samples, std::numeric_limits<double>::quiet_NaN());
  run->prediction.assign(samples, std::numeric_limits<double>::quiet_NaN());
  run->steps = steps;
  run->negative_log_likelihood = 0.0;
  auto visit = [&](int i, double nu, double S) {
    run->innovation[i] = nu;
    run->variance[i] = S;
    run->negative_log_likelihood += 0.5 * (nu * nu / S + std::log(S) + std::log(2.0 * M_PI));
  };
  const int nu_count = e.num_inputs;
  const int nodes = e.num_nodes();
  auto node = [&](int k, const double* x, const double* u) {
    if (steps <= 0 || k + steps >= nodes) return;
    std::array<double, n> xs;
    std::copy(x, x + n, xs.begin());
    const double* uu = u;
    for (int m = k; m < k + steps; ++m) {
      for (int s = 0; s < e.node_substeps[m]; ++s, uu += 3 * nu_count) {
        if (!Rk4Step(model, uu, uu + nu_count, uu + 2 * nu_count, p, e.node_step[m], xs.data())) {
          return;
        }
      }
    }
    std::array<double, ny> y;
    model.Output(xs.data(), uu, p, y.data());
    const double ahead = e.node_time[k + steps] - e.node_time[k];
    for (int i = e.node_first_sample[k + steps]; i < e.node_first_sample[k + steps + 1]; ++i) {
      const int j = e.samples[i].output;
      const DisturbanceLayout::OutputNoise& o = layout.outputs[j];
      double predicted = y[j];
      if (o.ar1_state >= 0) predicted += x[n + o.ar1_state] * std::exp(-ahead / theta[o.ar1_tau]);
      if (o.bias_state >= 0) predicted += x[n + o.bias_state];
      if (o.wave_state >= 0) {
        const int w = n + o.wave_state;
        const std::array<double, 4> f =
            WaveTransition(theta[o.wave_omega], theta[o.wave_zeta], ahead);
        predicted += f[0] * x[w] + f[1] * x[w + 1];
      }
      run->prediction[i] = predicted;
    }
  };
  return RunKalmanFilter(model, e, layout, p, x0, p0, theta, visit, node);
}

}  // namespace vesselid

// The extended Kalman filter of the filter-error method, run over one prepared experiment,
// templated on the scalar so that one code path gives the innovations in double and their
// exact derivatives on Jets (filter_error_cost.h). The hot path: fixed-size arrays, no heap,
// no virtual call, no lookup per step.
//
// Augmented state X = [x (model), z (disturbance, disturbance.h)], covariance P. Between two
// measurement nodes, per RK4 step h of the experiment's grid:
//   x <- RK4 step of x' = f(x, u, p)                          (the mean, as output error's)
//   F  = df/dx at the step's start (forward differences on the scalar type, step
//        1e-6 max(|x_m|, 1e-3): the derivative of what is computed is exact)
//   Phi = I + A + A^2/2 + A^3/6 + A^4/24, A = F h   (RK4's own transfer for a linear system)
//   P_xx <- Phi P_xx Phi' + h/2 (Phi Q Phi' + Q),  Q = diag(q) process noise   (trapezoid)
//   P_xz <- Phi P_xz
// and over the node interval D the disturbance exactly (linear, time-invariant):
//   ar1:  a = exp(-D / tau),  z <- a z,  var += sigma^2 (1 - a^2)
//   wave: Phi_w = exp(A_w D) in closed form (damped oscillator), Q_w = S - Phi_w S Phi_w',
//         S = diag(sigma^2, omega^2 sigma^2) its stationary covariance
//   bias: var += q D
//   P_zz <- Phi_z P_zz Phi_z' + Q_z,  P_xz <- P_xz Phi_z'
// At a node, each sample of output j in turn (sequential scalar updates):
//   H = [dg_j/dx (forward differences), 1 on output j's disturbance states]
//   nu = y - g_j(x, u, p) - sum z_j   (wrapped for wrapped angle outputs)
//   S = H P H' + sigma_j^2 + floor_j,  K = P H' / S,  X += K nu,  P -= (P H')(P H')' / S
// and visit(sample, nu, S). The initial P is diag(p0) on the model states (the start's
// variance where the state is not estimated, 0 where it is) and the disturbance's stationary
// (ar1, wave) or initial (bias) variance.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "ceres/jet.h"
#include "engine/model/disturbance.h"
#include "engine/model/experiment.h"
#include "engine/model/rk4.h"
#include "engine/model/simulate.h"

namespace vesselid {

// Runs the filter; false when a state or variance stops being finite, the model rejects a
// state, or an innovation variance is not positive. `p0` (model states) may be null: 0.
template <class Model, class T, class Visitor, class NodeVisitor>
bool RunKalmanFilter(const Model& model, const Experiment& e, const DisturbanceLayout& layout,
                     const T* p, const T* x0, const double* p0, const T* theta, Visitor&& visit,
                     NodeVisitor&& node_visit) {
  using std::cos;
  using std::exp;
  using std::sin;
  using std::sqrt;
  constexpr int n = Model::kNumStates;
  constexpr int ny = Model::kNumOutputs;
  constexpr int D = n + kMaxDisturbanceStates;
  static_assert(ny <= 16 && n <= 32, "filter arrays");
  const int nz = layout.num_states;
  const int d = n + nz;
  const int nu = e.num_inputs;

  std::array<T, D> x{};
  std::array<T, D * D> P{};
  auto at = [&P](int r, int c) -> T& { return P[r * D + c]; };
  for (int i = 0; i < n; ++i) {
    x[i] = x0[i];
    if (p0 != nullptr) at(i, i) = T(p0[i]);
  }
  for (int i = n; i < d; ++i) x[i] = T(0.0);

  std::array<T, ny> white{};
  for (int j = 0; j < ny; ++j) {
    const DisturbanceLayout::OutputNoise& o = layout.outputs[j];
    white[j] = T(o.floor);
    if (o.white >= 0) white[j] += theta[o.white] * theta[o.white];
    if (o.ar1_state >= 0) at(n + o.ar1_state, n + o.ar1_state) = theta[o.ar1_sigma] * theta[o.ar1_sigma];
    if (o.wave_state >= 0) {
      const T s2 = theta[o.wave_sigma] * theta[o.wave_sigma];
      const int w = n + o.wave_state;
      at(w, w) = s2;
      at(w + 1, w + 1) = theta[o.wave_omega] * theta[o.wave_omega] * s2;
    }
    if (o.bias_state >= 0) {
      at(n + o.bias_state, n + o.bias_state) = T(o.bias_initial_sd * o.bias_initial_sd);
    }
  }
  std::array<T, n> q{};
  bool any_process = false;
  for (int i = 0; i < n; ++i) {
    q[i] = T(0.0);
    if (layout.process[i] >= 0) {
      q[i] = theta[layout.process[i]];
      any_process = true;
    }
  }

  std::array<T, ny> y, yp;
  std::array<T, D> xp, h_row, ph;
  std::array<T, n> f0, f1;
  std::array<T, n * n> phi, a, tmp, tmp2;
  const double* u = e.input_cache.data();
  const int nodes = e.num_nodes();
  double last_interval = -1.0;
  // Disturbance transition over the last interval length (recomputed when it changes).
  std::array<T, kMaxDisturbanceStates * kMaxDisturbanceStates> phi_z{}, q_z{};

  auto fd_step = [](const T& v) { return 1e-6 * std::max(std::abs(ScalarPart(v)), 1e-3); };

  for (int k = 0; k < nodes; ++k) {
    for (int i = 0; i < d; ++i) {
      if (!std::isfinite(ScalarPart(x[i]))) return false;
    }
    // Measurement update, one sample at a time.
    for (int i = e.node_first_sample[k]; i < e.node_first_sample[k + 1]; ++i) {
      const ExperimentSample& s = e.samples[i];
      const int j = s.output;
      const DisturbanceLayout::OutputNoise& o = layout.outputs[j];
      model.Output(x.data(), u, p, y.data());
      for (int m = 0; m < d; ++m) h_row[m] = T(0.0);
      for (int m = 0; m < n; ++m) {
        xp = x;
        const double step = fd_step(x[m]);
        xp[m] += step;
        model.Output(xp.data(), u, p, yp.data());
        h_row[m] = (yp[j] - y[j]) / step;
      }
      T predicted = y[j];
      if (o.ar1_state >= 0) {
        predicted += x[n + o.ar1_state];
        h_row[n + o.ar1_state] = T(1.0);
      }
      if (o.wave_state >= 0) {
        predicted += x[n + o.wave_state];
        h_row[n + o.wave_state] = T(1.0);
      }
      if (o.bias_state >= 0) {
        predicted += x[n + o.bias_state];
        h_row[n + o.bias_state] = T(1.0);
      }
      T nu_k = s.value - predicted;
      if (e.Wrapped(j)) nu_k -= 2.0 * M_PI * std::round(ScalarPart(nu_k) / (2.0 * M_PI));
      T S = white[j];
      for (int r = 0; r < d; ++r) {
        ph[r] = T(0.0);
        for (int c = 0; c < d; ++c) ph[r] += at(r, c) * h_row[c];
      }
      for (int r = 0; r < d; ++r) S += h_row[r] * ph[r];
      if (!(ScalarPart(S) > 0.0) || !std::isfinite(ScalarPart(S))) return false;
      const T inverse = 1.0 / S;
      for (int r = 0; r < d; ++r) x[r] += ph[r] * (nu_k * inverse);
      for (int r = 0; r < d; ++r) {
        const T pr = ph[r] * inverse;
        for (int c = 0; c < d; ++c) at(r, c) -= pr * ph[c];
      }
      visit(i, nu_k, S);
    }
    node_visit(k, x.data(), u);
    if (k + 1 == nodes) break;

    // Prediction of the model states and their covariance, step by step.
    const int steps = e.node_substeps[k];
    const double h = e.node_step[k];
    for (int st = 0; st < steps; ++st, u += 3 * nu) {
      if (!model(x.data(), u, p, f0.data())) return false;
      for (int m = 0; m < n; ++m) {
        xp = x;
        const double step = fd_step(x[m]);
        xp[m] += step;
        if (!model(xp.data(), u, p, f1.data())) return false;
        for (int r = 0; r < n; ++r) a[r * n + m] = (f1[r] - f0[r]) * (h / step);
      }
      // phi = I + A (I + A/2 (I + A/3 (I + A/4))), by Horner from the inside out.
      for (int r = 0; r < n * n; ++r) tmp[r] = a[r] * 0.25;
      for (double divisor : {3.0, 2.0, 1.0}) {
        for (int r = 0; r < n; ++r) tmp[r * n + r] += 1.0;
        for (int r = 0; r < n; ++r) {
          for (int c = 0; c < n; ++c) {
            T sum = T(0.0);
            for (int m = 0; m < n; ++m) sum += a[r * n + m] * tmp[m * n + c];
            tmp2[r * n + c] = sum / divisor;
          }
        }
        tmp = tmp2;
      }
      for (int r = 0; r < n; ++r) tmp[r * n + r] += 1.0;
      phi = tmp;
      if (!Rk4Step(model, u, u + nu, u + 2 * nu, p, h, x.data())) return false;
      // tmp2 = phi P_xx ; then P_xx = tmp2 phi' (+ noise)
      for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c) {
          T sum = T(0.0);
          for (int m = 0; m < n; ++m) sum += phi[r * n + m] * at(m, c);
          tmp2[r * n + c] = sum;
        }
      }
      for (int r = 0; r < n; ++r) {
        for (int c = r; c < n; ++c) {
          T sum = T(0.0);
          for (int m = 0; m < n; ++m) sum += tmp2[r * n + m] * phi[c * n + m];
          if (any_process) {
            T noise = T(0.0);
            for (int m = 0; m < n; ++m) noise += phi[r * n + m] * q[m] * phi[c * n + m];
            if (r == c) noise += q[r];
            sum += (0.5 * h) * noise;
          }
          at(r, c) = sum;
          at(c, r) = sum;
        }
      }
      // P_xz <- phi P_xz (and its mirror)
      for (int c = n; c < d; ++c) {
        for (int r = 0; r < n; ++r) {
          T sum = T(0.0);
          for (int m = 0; m < n; ++m) sum += phi[r * n + m] * at(m, c);
          xp[r] = sum;
        }
        for (int r = 0; r < n; ++r) {
          at(r, c) = xp[r];
          at(c, r) = xp[r];
        }
      }
    }
    if (nz == 0) continue;
    // The disturbance over the node interval, exactly.
    const double interval = e.node_time[k + 1] - e.node_time[k];
    constexpr int Z = kMaxDisturbanceStates;
    if (interval != last_interval) {
      last_interval = interval;
      for (int r = 0; r < Z * Z; ++r) phi_z[r] = q_z[r] = T(0.0);
      for (int j = 0; j < ny; ++j) {
        const DisturbanceLayout::OutputNoise& o = layout.outputs[j];
        if (o.ar1_state >= 0) {
          const int z = o.ar1_state;
          const T decay = exp(-interval / theta[o.ar1_tau]);
          phi_z[z * Z + z] = decay;
          q_z[z * Z + z] = theta[o.ar1_sigma] * theta[o.ar1_sigma] * (1.0 - decay * decay);
        }
        if (o.bias_state >= 0) {
          const int z = o.bias_state;
          phi_z[z * Z + z] = T(1.0);
          q_z[z * Z + z] = theta[o.bias_q] * interval;
        }
        if (o.wave_state >= 0) {
          const int z = o.wave_state;
          const T& omega = theta[o.wave_omega];
          const T& zeta = theta[o.wave_zeta];
          const T damped = omega * sqrt(1.0 - zeta * zeta);
          const T envelope = exp(-zeta * omega * interval);
          const T cosine = cos(damped * interval), sine = sin(damped * interval);
          const T ratio = zeta * omega / damped;
          const T f11 = envelope * (cosine + ratio * sine), f12 = envelope * sine / damped;
          const T f21 = -envelope * omega * omega * sine / damped;
          const T f22 = envelope * (cosine - ratio * sine);
          phi_z[z * Z + z] = f11;
          phi_z[z * Z + z + 1] = f12;
          phi_z[(z + 1) * Z + z] = f21;
          phi_z[(z + 1) * Z + z + 1] = f22;
          const T s1 = theta[o.wave_sigma] * theta[o.wave_sigma];
          const T s2 = omega * omega * s1;
          // Q = S - Phi S Phi'
          q_z[z * Z + z] = s1 - (f11 * f11 * s1 + f12 * f12 * s2);
          q_z[z * Z + z + 1] = -(f11 * f21 * s1 + f12 * f22 * s2);
          q_z[(z + 1) * Z + z] = q_z[z * Z + z + 1];
          q_z[(z + 1) * Z + z + 1] = s2 - (f21 * f21 * s1 + f22 * f22 * s2);
        }
      }
    }
    // z <- Phi_z z
    std::array<T, Z> zn;
    for (int r = 0; r < nz; ++r) {
      zn[r] = T(0.0);
      for (int c = 0; c < nz; ++c) zn[r] += phi_z[r * Z + c] * x[n + c];
    }
    for (int r = 0; r < nz; ++r) x[n + r] = zn[r];
    // P_xz <- P_xz Phi_z'
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < nz; ++c) {
        zn[c] = T(0.0);
        for (int m = 0; m < nz; ++m) zn[c] += at(r, n + m) * phi_z[c * Z + m];
      }
      for (int c = 0; c < nz; ++c) {
        at(r, n + c) = zn[c];
        at(n + c, r) = zn[c];
      }
    }
    // P_zz <- Phi_z P_zz Phi_z' + Q_z
    std::array<T, Z * Z> pz;
    for (int r = 0; r < nz; ++r) {
      for (int c = 0; c < nz; ++c) {
        T sum = T(0.0);
        for (int m = 0; m < nz; ++m) sum += phi_z[r * Z + m] * at(n + m, n + c);
        pz[r * Z + c] = sum;
      }
    }
    for (int r = 0; r < nz; ++r) {
      for (int c = r; c < nz; ++c) {
        T sum = q_z[r * Z + c];
        for (int m = 0; m < nz; ++m) sum += pz[r * Z + m] * phi_z[c * Z + m];
        at(n + r, n + c) = sum;
        at(n + c, n + r) = sum;
      }
    }
  }
  return true;
}

}  // namespace vesselid

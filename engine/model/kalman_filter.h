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
// and visit(sample, nu, S).
//
// The steady-state gain (layout.steady_gain, `noise: {gain: auto}`): once P after a node's
// update equals P after the last one's (relative 1e-7) with the same samples, interval and F
// (relative 1e-6), the filter is stationary and its gains K and variances S per sample of the
// node are frozen: from then on only the mean moves (RK4 and x += K nu), at about output
// error's cost per step. Every kSteadyRecheck nodes F is evaluated again; a model whose F
// moves (a nonlinear one leaving the state it was frozen at), a node with other samples or
// another interval thaws the filter, which goes on from the frozen P. The frozen gains are
// Jets: their derivatives are the steady-state gain's.
//
// The initial P is diag(p0) on the model states (the start's variance where the state is not
// estimated, 0 where it is) and the disturbance's stationary (ar1, wave) or initial (bias)
// variance.
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

// Nodes between the frozen filter's checks that F is still the one it was frozen with.
inline constexpr int kSteadyRecheck = 25;

// The wave part's transition over `interval` (z1' = z2, z2' = -omega^2 z1 - 2 zeta omega z2),
// row-major {f11, f12, f21, f22}: the damped oscillator's closed form, 0 < zeta < 1.
template <class T>
std::array<T, 4> WaveTransition(const T& omega, const T& zeta, double interval) {
  using std::cos;
  using std::exp;
  using std::sin;
  using std::sqrt;
  const T damped = omega * sqrt(1.0 - zeta * zeta);
  const T envelope = exp(-zeta * omega * interval);
  const T cosine = cos(damped * interval), sine = sin(damped * interval);
  const T ratio = zeta * omega / damped;
  return {envelope * (cosine + ratio * sine), envelope * sine / damped,
          -envelope * omega * omega * sine / damped, envelope * (cosine - ratio * sine)};
}

template <class Model, class T>
class KalmanFilter {
 public:
  static constexpr int n = Model::kNumStates;
  static constexpr int ny = Model::kNumOutputs;
  static constexpr int D = n + kMaxDisturbanceStates;  // augmented state, at most
  static constexpr int Z = kMaxDisturbanceStates;
  static_assert(ny <= 16 && n <= 32, "filter arrays");

  // `p`, `x0` and `theta` (the noise parameters, layout order) must outlive Run; `p0` (model
  // states' initial variances) may be null: 0.
  KalmanFilter(const Model& model, const Experiment& e, const DisturbanceLayout& layout,
               const T* p, const T* x0, const double* p0, const T* theta)
      : model_(model), e_(e), layout_(layout), p_(p), theta_(theta) {
    nz_ = layout.num_states;
    d_ = n + nz_;
    nu_ = e.num_inputs;
    Start(x0, p0);
  }

  // visit(sample, nu, S) per sample; node_visit(node, X, u) after each node's update. False
  // when a state or variance stops being finite, the model rejects a state, or S <= 0.
  template <class Visitor, class NodeVisitor>
  bool Run(Visitor&& visit, NodeVisitor&& node_visit) {
    const double* u = e_.input_cache.data();
    const int nodes = e_.num_nodes();
    for (int k = 0; k < nodes; ++k) {
      for (int i = 0; i < d_; ++i) {
        if (!std::isfinite(ScalarPart(x_[i]))) return false;
      }
      if (!Update(k, u, visit)) return false;
      node_visit(k, x_.data(), u);
      if (k + 1 == nodes) break;
      interval_before_ = interval_last_;
      interval_last_ = e_.node_time[k + 1] - e_.node_time[k];
      if (frozen_ && ++since_check_ >= kSteadyRecheck) {
        since_check_ = 0;
        frozen_ = SameJacobian(u);
      }
      if (frozen_ && nz_ > 0 && interval_last_ != disturbance_interval_) frozen_ = false;
      if (!(frozen_ ? MoveMean(k, &u) : Propagate(k, &u))) return false;
      PropagateDisturbance(interval_last_, !frozen_);
    }
    return true;
  }

 private:
  T& P(int r, int c) { return cov_[r * D + c]; }

  // x = x0, z = 0; P = diag(p0) and the disturbance's start variance; per output the white
  // variance, per state the process noise.
  void Start(const T* x0, const double* p0) {
    for (int i = 0; i < n; ++i) {
      x_[i] = x0[i];
      if (p0 != nullptr) P(i, i) = T(p0[i]);
    }
    for (int i = n; i < d_; ++i) x_[i] = T(0.0);
    for (int j = 0; j < ny; ++j) {
      const DisturbanceLayout::OutputNoise& o = layout_.outputs[j];
      white_[j] = T(o.floor);
      if (o.white >= 0) white_[j] += theta_[o.white] * theta_[o.white];
      if (o.ar1_state >= 0) {
        P(n + o.ar1_state, n + o.ar1_state) = theta_[o.ar1_sigma] * theta_[o.ar1_sigma];
      }
      if (o.wave_state >= 0) {
        const T s2 = theta_[o.wave_sigma] * theta_[o.wave_sigma];
        const int w = n + o.wave_state;
        P(w, w) = s2;
        P(w + 1, w + 1) = theta_[o.wave_omega] * theta_[o.wave_omega] * s2;
      }
      if (o.bias_state >= 0) {
        P(n + o.bias_state, n + o.bias_state) = T(o.bias_initial_sd * o.bias_initial_sd);
      }
    }
    for (int i = 0; i < n; ++i) {
      q_[i] = T(0.0);
      if (layout_.process[i] >= 0) {
        q_[i] = theta_[layout_.process[i]];
        any_process_ = true;
      }
    }
  }

  static double FdStep(const T& v) { return 1e-6 * std::max(std::abs(ScalarPart(v)), 1e-3); }

  // The disturbance states' part of output j's prediction, and H's entries for them.
  T Disturbance(const DisturbanceLayout::OutputNoise& o, std::array<T, D>* h) const {
    T sum = T(0.0);
    for (int z : {o.ar1_state, o.wave_state, o.bias_state}) {
      if (z < 0) continue;
      sum += x_[n + z];
      if (h != nullptr) (*h)[n + z] = T(1.0);
    }
    return sum;
  }

  T Innovation(const ExperimentSample& s, const T& predicted) const {
    T nu = s.value - predicted;
    if (e_.Wrapped(s.output)) nu -= 2.0 * M_PI * std::round(ScalarPart(nu) / (2.0 * M_PI));
    return nu;
  }

  // Node k's samples, one scalar update each (frozen: with the frozen gains), then the test
  // for a steady filter.
  template <class Visitor>
  bool Update(int k, const double* u, Visitor& visit) {
    const int first = e_.node_first_sample[k], slots = e_.node_first_sample[k + 1] - first;
    if (frozen_ && slots != frozen_slots_) frozen_ = false;  // another pattern of samples
    for (int i = first; i < first + slots; ++i) {
      const ExperimentSample& s = e_.samples[i];
      const DisturbanceLayout::OutputNoise& o = layout_.outputs[s.output];
      model_.Output(x_.data(), u, p_, y_.data());
      if (frozen_) {
        const T nu = Innovation(s, y_[s.output] + Disturbance(o, nullptr));
        const int slot = i - first;
        for (int r = 0; r < d_; ++r) x_[r] += gain_[slot * D + r] * nu;
        visit(i, nu, gain_variance_[slot]);
        continue;
      }
      for (int m = 0; m < d_; ++m) h_[m] = T(0.0);
      for (int m = 0; m < n; ++m) {
        xp_ = x_;
        const double step = FdStep(x_[m]);
        xp_[m] += step;
        model_.Output(xp_.data(), u, p_, yp_.data());
        h_[m] = (yp_[s.output] - y_[s.output]) / step;
      }
      const T nu = Innovation(s, y_[s.output] + Disturbance(o, &h_));
      T S = white_[s.output];
      for (int r = 0; r < d_; ++r) {
        ph_[r] = T(0.0);
        for (int c = 0; c < d_; ++c) ph_[r] += P(r, c) * h_[c];
      }
      for (int r = 0; r < d_; ++r) S += h_[r] * ph_[r];
      if (!(ScalarPart(S) > 0.0) || !std::isfinite(ScalarPart(S))) return false;
      const T inverse = 1.0 / S;
      if (i - first < ny) {
        for (int r = 0; r < d_; ++r) gain_[(i - first) * D + r] = ph_[r] * inverse;
        gain_variance_[i - first] = S;
      }
      for (int r = 0; r < d_; ++r) x_[r] += ph_[r] * (nu * inverse);
      for (int r = 0; r < d_; ++r) {
        const T pr = ph_[r] * inverse;
        for (int c = 0; c < d_; ++c) P(r, c) -= pr * ph_[c];
      }
      visit(i, nu, S);
    }
    if (!frozen_ && slots <= ny) TestSteady(slots);
    return true;
  }

  // Freezes the gains when P after this node's update equals P after the last one's (relative
  // 1e-7) with the same samples, interval and F.
  void TestSteady(int slots) {
    double change = 0.0, size = 0.0;
    for (int r = 0; r < d_; ++r) {
      for (int c = 0; c < d_; ++c) {
        const double v = ScalarPart(P(r, c));
        change = std::max(change, std::abs(v - p_last_[r * D + c]));
        p_last_[r * D + c] = v;
      }
      size = std::max(size, std::abs(ScalarPart(P(r, r))));
    }
    if (layout_.steady_gain && f_steady_ && slots == last_slots_ &&
        interval_last_ == interval_before_ && change <= 1e-7 * size) {
      frozen_ = true;
      frozen_slots_ = slots;
      f_frozen_ = f_last_;
      since_check_ = 0;
    }
    last_slots_ = slots;
  }

  // Whether F at the current state is still the frozen one (relative 1e-6).
  bool SameJacobian(const double* u) {
    if (!model_(x_.data(), u, p_, f0_.data())) return false;
    double largest = 0.0, moved = 0.0;
    for (int m = 0; m < n; ++m) {
      xp_ = x_;
      const double step = FdStep(x_[m]);
      xp_[m] += step;
      if (!model_(xp_.data(), u, p_, f1_.data())) return false;
      for (int r = 0; r < n; ++r) {
        const double v = ScalarPart(f1_[r] - f0_[r]) / step;
        largest = std::max(largest, std::abs(f_frozen_[r * n + m]));
        moved = std::max(moved, std::abs(v - f_frozen_[r * n + m]));
      }
    }
    return moved <= 1e-6 * largest;
  }

  // The frozen filter between nodes: the model's mean alone (P and the gains stay).
  bool MoveMean(int k, const double** u) {
    const int steps = e_.node_substeps[k];
    const double h = e_.node_step[k];
    for (int st = 0; st < steps; ++st, *u += 3 * nu_) {
      if (!Rk4Step(model_, *u, *u + nu_, *u + 2 * nu_, p_, h, x_.data())) return false;
    }
    return true;
  }

  // phi = I + A + A^2/2 + A^3/6 + A^4/24 with A = F h, F by forward differences at x (and
  // whether F is the last step's, for TestSteady). False if the model rejects a state.
  bool Transition(const double* u, double h) {
    if (!model_(x_.data(), u, p_, f0_.data())) return false;
    for (int m = 0; m < n; ++m) {
      xp_ = x_;
      const double step = FdStep(x_[m]);
      xp_[m] += step;
      if (!model_(xp_.data(), u, p_, f1_.data())) return false;
      for (int r = 0; r < n; ++r) a_[r * n + m] = (f1_[r] - f0_[r]) * (h / step);
    }
    double largest = 0.0, moved = 0.0;
    for (int r = 0; r < n * n; ++r) {
      const double v = ScalarPart(a_[r]) / h;
      largest = std::max(largest, std::abs(v));
      moved = std::max(moved, std::abs(v - f_last_[r]));
      f_last_[r] = v;
    }
    f_steady_ = moved <= 1e-6 * largest;
    // Horner from the inside out: I + A (I + A/2 (I + A/3 (I + A/4))).
    for (int r = 0; r < n * n; ++r) tmp_[r] = a_[r] * 0.25;
    for (double divisor : {3.0, 2.0, 1.0}) {
      for (int r = 0; r < n; ++r) tmp_[r * n + r] += 1.0;
      for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c) {
          T sum = T(0.0);
          for (int m = 0; m < n; ++m) sum += a_[r * n + m] * tmp_[m * n + c];
          tmp2_[r * n + c] = sum / divisor;
        }
      }
      tmp_ = tmp2_;
    }
    for (int r = 0; r < n; ++r) tmp_[r * n + r] += 1.0;
    phi_ = tmp_;
    return true;
  }

  // P_xx <- phi P_xx phi' + h/2 (phi Q phi' + Q),  P_xz <- phi P_xz.
  void PropagateCovariance(double h) {
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) {
        T sum = T(0.0);
        for (int m = 0; m < n; ++m) sum += phi_[r * n + m] * P(m, c);
        tmp2_[r * n + c] = sum;
      }
    }
    for (int r = 0; r < n; ++r) {
      for (int c = r; c < n; ++c) {
        T sum = T(0.0);
        for (int m = 0; m < n; ++m) sum += tmp2_[r * n + m] * phi_[c * n + m];
        if (any_process_) {
          T noise = T(0.0);
          for (int m = 0; m < n; ++m) noise += phi_[r * n + m] * q_[m] * phi_[c * n + m];
          if (r == c) noise += q_[r];
          sum += (0.5 * h) * noise;
        }
        P(r, c) = sum;
        P(c, r) = sum;
      }
    }
    for (int c = n; c < d_; ++c) {
      for (int r = 0; r < n; ++r) {
        T sum = T(0.0);
        for (int m = 0; m < n; ++m) sum += phi_[r * n + m] * P(m, c);
        xp_[r] = sum;
      }
      for (int r = 0; r < n; ++r) {
        P(r, c) = xp_[r];
        P(c, r) = xp_[r];
      }
    }
  }

  // The model's mean and covariance from node k to k + 1, step by step.
  bool Propagate(int k, const double** u) {
    const int steps = e_.node_substeps[k];
    const double h = e_.node_step[k];
    for (int st = 0; st < steps; ++st, *u += 3 * nu_) {
      if (!Transition(*u, h)) return false;
      if (!Rk4Step(model_, *u, *u + nu_, *u + 2 * nu_, p_, h, x_.data())) return false;
      PropagateCovariance(h);
    }
    return true;
  }

  // phi_z and Q_z over `interval` (closed forms, disturbance.h).
  void DisturbanceTransition(double interval) {
    using std::exp;
    using std::sqrt;
    for (int r = 0; r < Z * Z; ++r) phi_z_[r] = q_z_[r] = T(0.0);
    for (int j = 0; j < ny; ++j) {
      const DisturbanceLayout::OutputNoise& o = layout_.outputs[j];
      if (o.ar1_state >= 0) {
        const int z = o.ar1_state;
        const T decay = exp(-interval / theta_[o.ar1_tau]);
        phi_z_[z * Z + z] = decay;
        q_z_[z * Z + z] = theta_[o.ar1_sigma] * theta_[o.ar1_sigma] * (1.0 - decay * decay);
      }
      if (o.bias_state >= 0) {
        const int z = o.bias_state;
        phi_z_[z * Z + z] = T(1.0);
        q_z_[z * Z + z] = theta_[o.bias_q] * interval;
      }
      if (o.wave_state >= 0) {
        const int z = o.wave_state;
        const T& omega = theta_[o.wave_omega];
        const T& zeta = theta_[o.wave_zeta];
        const std::array<T, 4> f = WaveTransition(omega, zeta, interval);
        const T &f11 = f[0], &f12 = f[1], &f21 = f[2], &f22 = f[3];
        phi_z_[z * Z + z] = f11;
        phi_z_[z * Z + z + 1] = f12;
        phi_z_[(z + 1) * Z + z] = f21;
        phi_z_[(z + 1) * Z + z + 1] = f22;
        const T s1 = theta_[o.wave_sigma] * theta_[o.wave_sigma];
        const T s2 = omega * omega * s1;
        // Q = S - Phi S Phi'
        q_z_[z * Z + z] = s1 - (f11 * f11 * s1 + f12 * f12 * s2);
        q_z_[z * Z + z + 1] = -(f11 * f21 * s1 + f12 * f22 * s2);
        q_z_[(z + 1) * Z + z] = q_z_[z * Z + z + 1];
        q_z_[(z + 1) * Z + z + 1] = s2 - (f21 * f21 * s1 + f22 * f22 * s2);
      }
    }
  }

  // z <- phi_z z over the node interval; with `covariance`, P_xz <- P_xz phi_z' and
  // P_zz <- phi_z P_zz phi_z' + Q_z.
  void PropagateDisturbance(double interval, bool covariance) {
    if (nz_ == 0) return;
    if (interval != disturbance_interval_) {
      disturbance_interval_ = interval;
      DisturbanceTransition(interval);
    }
    std::array<T, Z> zn;
    for (int r = 0; r < nz_; ++r) {
      zn[r] = T(0.0);
      for (int c = 0; c < nz_; ++c) zn[r] += phi_z_[r * Z + c] * x_[n + c];
    }
    for (int r = 0; r < nz_; ++r) x_[n + r] = zn[r];
    if (!covariance) return;
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < nz_; ++c) {
        zn[c] = T(0.0);
        for (int m = 0; m < nz_; ++m) zn[c] += P(r, n + m) * phi_z_[c * Z + m];
      }
      for (int c = 0; c < nz_; ++c) {
        P(r, n + c) = zn[c];
        P(n + c, r) = zn[c];
      }
    }
    std::array<T, Z * Z> pz;
    for (int r = 0; r < nz_; ++r) {
      for (int c = 0; c < nz_; ++c) {
        T sum = T(0.0);
        for (int m = 0; m < nz_; ++m) sum += phi_z_[r * Z + m] * P(n + m, n + c);
        pz[r * Z + c] = sum;
      }
    }
    for (int r = 0; r < nz_; ++r) {
      for (int c = r; c < nz_; ++c) {
        T sum = q_z_[r * Z + c];
        for (int m = 0; m < nz_; ++m) sum += pz[r * Z + m] * phi_z_[c * Z + m];
        P(n + r, n + c) = sum;
        P(n + c, n + r) = sum;
      }
    }
  }

  const Model& model_;
  const Experiment& e_;
  const DisturbanceLayout& layout_;
  const T* p_;
  const T* theta_;
  int nz_ = 0, d_ = 0, nu_ = 0;
  std::array<T, D> x_{};
  std::array<T, D * D> cov_{};
  std::array<T, ny> white_{};
  std::array<T, n> q_{};
  bool any_process_ = false;
  // Work arrays (members: no allocation per step).
  std::array<T, ny> y_{}, yp_{};
  std::array<T, D> xp_{}, h_{}, ph_{};
  std::array<T, n> f0_{}, f1_{};
  std::array<T, n * n> phi_{}, a_{}, tmp_{}, tmp2_{};
  std::array<T, Z * Z> phi_z_{}, q_z_{};
  double disturbance_interval_ = -1.0;
  // The steady-state filter.
  bool frozen_ = false;
  int frozen_slots_ = -1, last_slots_ = -2, since_check_ = 0;
  std::array<T, ny * D> gain_{};
  std::array<T, ny> gain_variance_{};
  std::array<double, D * D> p_last_{};
  std::array<double, n * n> f_last_{}, f_frozen_{};
  bool f_steady_ = false;
  double interval_last_ = -1.0, interval_before_ = -2.0;
};

// Runs the filter over `e` (see KalmanFilter::Run).
template <class Model, class T, class Visitor, class NodeVisitor>
bool RunKalmanFilter(const Model& model, const Experiment& e, const DisturbanceLayout& layout,
                     const T* p, const T* x0, const double* p0, const T* theta, Visitor&& visit,
                     NodeVisitor&& node_visit) {
  KalmanFilter<Model, T> filter(model, e, layout, p, x0, p0, theta);
  return filter.Run(visit, node_visit);
}

}  // namespace vesselid

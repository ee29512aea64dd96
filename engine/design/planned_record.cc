#include "engine/design/planned_record.h"

#include <algorithm>
#include <cmath>

namespace vesselid {
namespace {

// One RK4 step of length h from x (rk4.h) with inputs u0, u_mid, u1 at its start, middle and
// end; false when the model refuses a state or the state stops being finite.
struct Rk4Scratch {
  std::vector<double> xs, k1, k2, k3, k4;
  explicit Rk4Scratch(size_t n) : xs(n), k1(n), k2(n), k3(n), k4(n) {}
};

bool Rk4Advance(const ModelHandle& model, const double* u0, const double* u_mid, const double* u1,
                const std::vector<double>& p, double h, std::vector<double>* state, Rk4Scratch* w) {
  std::vector<double>& x = *state;
  const size_t n = x.size();
  if (!model.Derivative(x.data(), u0, p.data(), w->k1.data())) return false;
  for (size_t i = 0; i < n; ++i) w->xs[i] = x[i] + 0.5 * h * w->k1[i];
  if (!model.Derivative(w->xs.data(), u_mid, p.data(), w->k2.data())) return false;
  for (size_t i = 0; i < n; ++i) w->xs[i] = x[i] + 0.5 * h * w->k2[i];
  if (!model.Derivative(w->xs.data(), u_mid, p.data(), w->k3.data())) return false;
  for (size_t i = 0; i < n; ++i) w->xs[i] = x[i] + h * w->k3[i];
  if (!model.Derivative(w->xs.data(), u1, p.data(), w->k4.data())) return false;
  for (size_t i = 0; i < n; ++i) {
    x[i] += h / 6.0 * (w->k1[i] + 2.0 * (w->k2[i] + w->k3[i]) + w->k4[i]);
    if (!std::isfinite(x[i])) return false;
  }
  return true;
}

}  // namespace

bool RealizePlan(const ModelHandle& model, const std::vector<double>& p,
                 const std::vector<double>& x0, double duration, double sample_time,
                 double max_step, const Actuators& a, const InputCommand& command,
                 PlannedRecord* record, const std::function<bool()>& stop) {
  const ModelInfo& info = model.info();
  const int nx = static_cast<int>(info.states.size());
  const int nu = static_cast<int>(info.inputs.size());
  const int ny = static_cast<int>(info.outputs.size());
  const int samples = static_cast<int>(std::floor(duration / sample_time + 1e-9)) + 1;
  record->time.clear();
  record->inputs.resize(samples, nu);
  record->outputs.resize(samples, ny);
  record->finite = false;
  std::vector<double> x = x0;
  Rk4Scratch scratch(nx);
  std::vector<double> u = a.start, u_next(nu), u_mid(nu), c(nu), y(ny);
  const int substeps =
      max_step > 0.0 ? std::max(1, static_cast<int>(std::ceil(sample_time / max_step - 1e-9))) : 1;
  const double h = sample_time / substeps;
  std::vector<double> u0(nu), u1(nu);
  for (int k = 0; k < samples; ++k) {
    const double t = k * sample_time;
    model.Output(x.data(), u.data(), p.data(), y.data());
    record->time.push_back(t);
    for (int i = 0; i < nu; ++i) record->inputs(k, i) = u[i];
    for (int j = 0; j < ny; ++j) record->outputs(k, j) = y[j];
    if (k + 1 == samples || (stop && stop())) break;
    command(t, y.data(), c.data());
    for (int i = 0; i < nu; ++i) {
      const double target = std::clamp(c[i], a.lower[i], a.upper[i]);
      const double step = a.rate[i] > 0.0 ? a.rate[i] * sample_time : INFINITY;
      u_next[i] = u[i] + std::clamp(target - u[i], -step, step);
    }
    // RK4 as engine/model/rk4.h, inputs linear over the sample interval.
    bool finite = true;
    for (int s = 0; s < substeps && finite; ++s) {
      const double a0 = static_cast<double>(s) / substeps, a1 = (s + 1.0) / substeps;
      for (int i = 0; i < nu; ++i) {
        u0[i] = u[i] + a0 * (u_next[i] - u[i]);
        u_mid[i] = u[i] + 0.5 * (a0 + a1) * (u_next[i] - u[i]);
        u1[i] = u[i] + a1 * (u_next[i] - u[i]);
      }
      finite = Rk4Advance(model, u0.data(), u_mid.data(), u1.data(), p, h, &x, &scratch);
    }
    if (!finite) break;
    u = u_next;
  }
  // Divergence leaves the samples reached; a stop ends a whole record.
  const int reached = static_cast<int>(record->time.size());
  record->inputs.conservativeResize(reached, nu);
  record->outputs.conservativeResize(reached, ny);
  record->finite = reached == samples || (stop && stop());
  return record->finite;
}

bool SettleState(const ModelHandle& model, const std::vector<double>& p, double duration,
                 double max_step, const std::vector<double>& u, std::vector<double>* x) {
  const int steps = std::max(1, static_cast<int>(std::ceil(duration / std::max(max_step, 1e-3))));
  const double h = duration / steps;
  Rk4Scratch scratch(x->size());
  for (int k = 0; k < steps; ++k) {
    if (!Rk4Advance(model, u.data(), u.data(), u.data(), p, h, x, &scratch)) return false;
  }
  return true;
}

}  // namespace vesselid

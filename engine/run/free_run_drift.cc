#include "engine/run/free_run_drift.h"

#include <cmath>
#include <random>

namespace vesselid {
namespace {

// The outputs at every sample of experiment `e` flown from x0 with the logged inputs; with
// `q` (per state, may be all zero) and `random`, in a realisation of the process noise. False
// where the model refuses a state or a value stops being finite.
bool FlyExperiment(const ModelHandle& model, const Experiment& e, const std::vector<double>& p,
                   std::vector<double> x, const std::vector<double>& q, std::mt19937_64* random,
                   std::vector<double>* outputs) {
  const ModelInfo& info = model.info();
  const size_t nx = x.size();
  const int nu = e.num_inputs;
  std::vector<double> k1(nx), k2(nx), k3(nx), k4(nx), xs(nx), y(info.outputs.size());
  std::normal_distribution<double> normal;
  outputs->assign(e.num_samples(), 0.0);
  const double* u = e.input_cache.data();
  for (int k = 0; k < e.num_nodes(); ++k) {
    model.Output(x.data(), u, p.data(), y.data());
    for (int i = e.node_first_sample[k]; i < e.node_first_sample[k + 1]; ++i) {
      const double value = y[e.samples[i].output];
      if (!std::isfinite(value)) return false;
      (*outputs)[i] = value;
    }
    if (k + 1 == e.num_nodes()) break;
    const double h = e.node_step[k];
    for (int s = 0; s < e.node_substeps[k]; ++s, u += 3 * nu) {
      // RK4 as engine/model/rk4.h: the start, midpoint and end rows of the step's inputs.
      if (!model.Derivative(x.data(), u, p.data(), k1.data())) return false;
      for (size_t i = 0; i < nx; ++i) xs[i] = x[i] + 0.5 * h * k1[i];
      if (!model.Derivative(xs.data(), u + nu, p.data(), k2.data())) return false;
      for (size_t i = 0; i < nx; ++i) xs[i] = x[i] + 0.5 * h * k2[i];
      if (!model.Derivative(xs.data(), u + nu, p.data(), k3.data())) return false;
      for (size_t i = 0; i < nx; ++i) xs[i] = x[i] + h * k3[i];
      if (!model.Derivative(xs.data(), u + 2 * nu, p.data(), k4.data())) return false;
      for (size_t i = 0; i < nx; ++i) {
        x[i] += h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
        if (random != nullptr && q[i] > 0.0) x[i] += std::sqrt(q[i] * h) * normal(*random);
      }
    }
  }
  return true;
}

// The residual of sample i: measured - flown, a wrapped output's taken into (-pi, pi].
double Residual(const Experiment& e, int i, double flown) {
  double r = e.samples[i].value - flown;
  if (e.Wrapped(e.samples[i].output)) r -= 2.0 * M_PI * std::round(r / (2.0 * M_PI));
  return r;
}

}  // namespace

std::vector<FreeRunDrift> MeasureFreeRunDrift(const OutputErrorProblem& problem) {
  std::vector<FreeRunDrift> drifts;
  if (!problem.filter_error()) return drifts;
  const DisturbanceLayout& layout = problem.disturbance();
  const std::vector<double> theta = problem.NoiseValues();
  const ModelHandle& model = problem.model();
  const size_t nx = model.info().states.size(), ny = model.info().outputs.size();
  std::vector<double> q(nx, 0.0);
  bool any = false;
  for (size_t i = 0; i < nx && i < layout.process.size(); ++i) {
    if (layout.process[i] >= 0) q[i] = theta[layout.process[i]];
    any = any || q[i] > 0.0;
  }
  if (!any) return drifts;
  // The sensors' variance of output j at time since the start `t`.
  auto sensor = [&](int j, double t) {
    const DisturbanceLayout::OutputNoise& o = layout.outputs[j];
    double r = o.floor;
    auto squared = [&](int index) { return index >= 0 ? theta[index] * theta[index] : 0.0; };
    r += squared(o.white) + squared(o.ar1_sigma) + squared(o.wave_sigma);
    if (o.bias_state >= 0) r += o.bias_initial_sd * o.bias_initial_sd + theta[o.bias_q] * t;
    return r;
  };
  for (size_t x = 0; x < problem.experiments().size(); ++x) {
    const Experiment& e = problem.experiments()[x];
    const std::vector<double> p = problem.ParametersOf(static_cast<int>(x));
    const std::vector<double> x0 = problem.InitialStateOf(static_cast<int>(x));
    std::vector<double> calm;
    if (!FlyExperiment(model, e, p, x0, q, nullptr, &calm)) continue;
    std::vector<double> spread(e.num_samples(), 0.0);
    std::mt19937_64 random(1000003u * (x + 1));  // the same expectation on every run
    int flown = 0;
    for (int m = 0; m < kDriftMembers; ++m) {
      std::vector<double> gusty;
      if (!FlyExperiment(model, e, p, x0, q, &random, &gusty)) continue;
      ++flown;
      for (int i = 0; i < e.num_samples(); ++i) {
        const double d = Residual(e, i, calm[i]) - Residual(e, i, gusty[i]);
        spread[i] += d * d;
      }
    }
    if (flown < kDriftMembers / 2) continue;
    std::vector<FreeRunDrift> per_output(ny);
    for (int k = 0; k < e.num_nodes(); ++k) {
      for (int i = e.node_first_sample[k]; i < e.node_first_sample[k + 1]; ++i) {
        const int j = e.samples[i].output;
        if (e.samples[i].weight == 0.0) continue;
        FreeRunDrift& d = per_output[j];
        const double r = Residual(e, i, calm[i]);
        d.observed_sse += r * r;
        d.expected_sse += spread[i] / flown + sensor(j, e.node_time[k] - e.node_time.front());
        ++d.samples;
      }
    }
    for (size_t j = 0; j < ny; ++j) {
      if (per_output[j].samples == 0 || !(per_output[j].expected_sse > 0.0)) continue;
      per_output[j].experiment = e.name;
      per_output[j].output = model.info().outputs[j];
      drifts.push_back(per_output[j]);
    }
  }
  return drifts;
}

}  // namespace vesselid

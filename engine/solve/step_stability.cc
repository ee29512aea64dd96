#include "engine/solve/step_stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "Eigen/Dense"

namespace vesselid {
namespace {

constexpr int kChecksPerExperiment = 200;  // Jacobians formed along each simulation

// Largest |eigenvalue| of df/dx at (x, u) by central differences; NaN if f fails.
double FastestRate(const ModelHandle& model, std::vector<double> x, const double* u,
                   const double* p) {
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd jacobian(n, n);
  std::vector<double> plus(n), minus(n);
  for (int j = 0; j < n; ++j) {
    const double x0 = x[j], h = 1e-6 * (1.0 + std::abs(x0));
    x[j] = x0 + h;
    if (!model.Derivative(x.data(), u, p, plus.data())) return std::nan("");
    x[j] = x0 - h;
    if (!model.Derivative(x.data(), u, p, minus.data())) return std::nan("");
    x[j] = x0;
    for (int i = 0; i < n; ++i) jacobian(i, j) = (plus[i] - minus[i]) / (2 * h);
  }
  if (!jacobian.allFinite()) return std::nan("");
  return jacobian.eigenvalues().cwiseAbs().maxCoeff();
}

// One RK4 step of the model through its handle (a check, not the hot path).
bool Step(const ModelHandle& model, const double* u0, const double* u_mid, const double* u1,
          const double* p, double h, std::vector<double>* x) {
  const size_t n = x->size();
  std::vector<double> k1(n), k2(n), k3(n), k4(n), xs(n);
  if (!model.Derivative(x->data(), u0, p, k1.data())) return false;
  for (size_t i = 0; i < n; ++i) xs[i] = (*x)[i] + 0.5 * h * k1[i];
  if (!model.Derivative(xs.data(), u_mid, p, k2.data())) return false;
  for (size_t i = 0; i < n; ++i) xs[i] = (*x)[i] + 0.5 * h * k2[i];
  if (!model.Derivative(xs.data(), u_mid, p, k3.data())) return false;
  for (size_t i = 0; i < n; ++i) xs[i] = (*x)[i] + h * k3[i];
  if (!model.Derivative(xs.data(), u1, p, k4.data())) return false;
  for (size_t i = 0; i < n; ++i) (*x)[i] += h / 6.0 * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  for (double v : *x) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

std::string StepStability::Describe() const {
  char text[256];
  std::snprintf(text, sizeof(text),
                "h |lambda| = %.3g (time constant %.3g s, step %.3g s) at t = %g s in '%s'", worst,
                1.0 / fastest_rate, step, time, experiment.c_str());
  return text;
}

StepStability CheckStepStability(const OutputErrorProblem& problem) {
  StepStability result;
  const ModelHandle& model = problem.model();
  for (int e = 0; e < static_cast<int>(problem.experiments().size()); ++e) {
    const Experiment& experiment = problem.experiments()[e];
    const std::vector<double> p = problem.ParametersOf(e);
    std::vector<double> x = problem.InitialStateOf(e);
    const int nu = experiment.num_inputs;
    const double* u = experiment.input_cache.data();
    int total_steps = 0;
    for (int s : experiment.node_substeps) total_steps += s;
    const int stride = std::max(1, total_steps / kChecksPerExperiment);
    int step_index = 0;
    bool ok = true;
    // A simulation that stops is checked over what it reached.
    for (int k = 0; ok && k + 1 < experiment.num_nodes(); ++k) {
      const double h = experiment.node_step[k];
      for (int s = 0; ok && s < experiment.node_substeps[k]; ++s, u += 3 * nu, ++step_index) {
        if (step_index % stride == 0) {
          const double rate = FastestRate(model, x, u, p.data());
          if (std::isfinite(rate) && rate * h > result.worst) {
            result.worst = rate * h;
            result.fastest_rate = rate;
            result.step = h;
            result.time = experiment.node_time[k] + s * h;
            result.experiment = experiment.name;
          }
        }
        ok = Step(model, u, u + nu, u + 2 * nu, p.data(), h, &x);
      }
    }
  }
  return result;
}

}  // namespace vesselid

// Classical fixed-step Runge-Kutta (RK4), templated on the scalar so that one code path
// integrates doubles and ceres::Jets:
//   k1 = f(x, u(t)),          k2 = f(x + h/2 k1, u(t + h/2)),
//   k3 = f(x + h/2 k2, u(t + h/2)),  k4 = f(x + h k3, u(t + h)),
//   x(t + h) = x + h/6 (k1 + 2 k2 + 2 k3 + k4).
// Inputs at t, t + h/2, t + h are passed in (precomputed), so a step does no lookup and no
// allocation; they are doubles, or Jets where the inputs themselves are estimated (input_noise.h).
#pragma once

#include <array>

namespace vesselid {

// GCC: the whole step, the model's right-hand side and its Jet arithmetic included, is
// inlined (flatten). Left to itself GCC outlines the Jet operators once a model has two
// instantiations (double and Jet inputs): cargo 1.5 -> 2.3 s; flattened, the input-gain
// refinement runs 2.5x faster than before either. Clang inlines the step by itself, and
// flattening under its sanitizers takes minutes and gigabytes per file.
#if defined(__GNUC__) && !defined(__clang__)
#define VESSELID_FLATTEN __attribute__((flatten))
#else
#define VESSELID_FLATTEN
#endif

// The step sizes stay doubles: a Jet times a double scales value and derivatives (one vector
// operation), a Jet times a Jet with zero derivatives costs two and gives the same numbers
// (measured on the second-order Nomoto model on Jets of 4: 10 % fewer instructions per step).
template <class Model, class T, class U>
VESSELID_FLATTEN bool Rk4Step(const Model& model, const U* u0, const U* u_mid, const U* u1,
                              const T* p, double h, T* x) {
  constexpr int n = Model::kNumStates;
  std::array<T, n> k1, k2, k3, k4, xs;
  if (!model(x, u0, p, k1.data())) return false;
  const double half_h = 0.5 * h;
  for (int i = 0; i < n; ++i) xs[i] = x[i] + half_h * k1[i];
  if (!model(xs.data(), u_mid, p, k2.data())) return false;
  for (int i = 0; i < n; ++i) xs[i] = x[i] + half_h * k2[i];
  if (!model(xs.data(), u_mid, p, k3.data())) return false;
  for (int i = 0; i < n; ++i) xs[i] = x[i] + h * k3[i];
  if (!model(xs.data(), u1, p, k4.data())) return false;
  const double sixth_h = h / 6.0;
  for (int i = 0; i < n; ++i) x[i] += sixth_h * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
  return true;
}

}  // namespace vesselid

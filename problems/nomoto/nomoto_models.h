// Nomoto steering models (MODELS.md §2, seed 003). Input: rudder angle delta [rad].
// Outputs: heading psi [rad] and yaw rate r [rad/s]. delta_0 is a rudder bias.
//
// First order:  T r' + r = K (delta + delta_0)
// Norrbin:      T r' + r + alpha r^3 = K (delta + delta_0)
// Second order: T1 T2 psi''' + (T1 + T2) psi'' + psi' = K (delta + T3 delta'), realised
//               without delta' as
//                 xi1' = xi2,  xi2' = (delta + delta_0 - xi1 - (T1 + T2) xi2) / (T1 T2),
//                 r = K (xi1 + T3 xi2),  psi' = r.
//               T1 and T2 are exchangeable; the engine reports T1 >= T2.
#pragma once

#include <cmath>

#include "Eigen/Dense"
#include "engine/model/model.h"
#include "engine/model/regression_form.h"

namespace vesselid::nomoto {

// Equation-error form of the first-order and Norrbin models (least-squares stage):
//   r' = K/T delta + K delta_0/T - 1/T r [- alpha/T r^3]
// theta = [K/T, K delta_0/T, -1/T (, -alpha/T)], regressors [delta, 1, r (, r^3)].
inline RegressionForm YawRateRegression(bool cubic) {
  RegressionForm form;
  form.states = {1};
  form.coefficients = {{"K/T", "K*delta_0/T", "-1/T"}};
  if (cubic) form.coefficients[0].push_back("-alpha/T");
  form.regions = {"all"};
  return form;
}

inline void YawRateRegressors(bool cubic, RegressionRecord* record,
                              std::vector<Eigen::MatrixXd>* phi) {
  const int n = record->size();
  phi->assign(1, Eigen::MatrixXd(n, cubic ? 4 : 3));
  Eigen::MatrixXd& m = (*phi)[0];
  for (int k = 0; k < n; ++k) {
    const double r = record->x(k, 1);
    m.row(k).head<3>() << record->u(k, 0), 1.0, r;
    if (cubic) m(k, 3) = r * r * r;
  }
}

// Units of a Nomoto model's parameters (ModelInfo::parameter_units), and delta_0 as an angle
// of the rudder: shown in degrees where the rudder column is read in degrees.
inline ModelInfo WithParameterUnits(ModelInfo info, std::vector<std::string> units) {
  info.parameter_units = std::move(units);
  info.parameter_channels = {{"delta_0", "delta"}};
  // The rudder is an angle (the unit checks judge a column logged in degrees by it).
  if (info.input_units.empty()) {
    for (const std::string& input : info.inputs)
      info.input_units.push_back(input == "delta" ? "rad" : (input == "U" ? "m/s" : ""));
  }
  return info;
}

// Start value of the yaw rate r (state 1) from the measured heading rate when r itself is not
// measured (first-order and Norrbin models; y = [psi, r]).
inline void GuessYawRate(const double* y, const double* ydot, double* x) {
  if (std::isnan(y[1]) && std::isfinite(ydot[0])) x[1] = ydot[0];
}

struct FirstOrder {
  static constexpr int kNumStates = 2;   // psi, r
  static constexpr int kMaxParameters = 3;  // T, K, delta_0
  static constexpr int kNumInputs = 1;   // delta
  static constexpr int kNumOutputs = 2;  // psi, r

  ModelInfo Info() const {
    return WithParameterUnits({"nomoto_first_order", {"psi", "r"}, {"delta"}, {"psi", "r"},
                               {"T", "K", "delta_0"}, {10.0, 0.1, 0.0}, {true, false}, {}, {},
                               {"rad", "rad/s"}, {"rad", "rad/s"}, {"rad"}},
                              {"s", "1/s", "rad"});
  }

  template <class T, class U>
  bool operator()(const T* x, const U* u, const T* p, T* xdot) const {
    const T& time_constant = p[0];
    if (!(time_constant > 0.0)) return false;
    xdot[0] = x[1];
    xdot[1] = (p[1] * (u[0] + p[2]) - x[1]) / time_constant;
    return true;
  }

  void GuessState(const double* y, const double* ydot, double* x) const {
    GuessYawRate(y, ydot, x);
  }

  RegressionForm Regression() const { return YawRateRegression(false); }
  void Regressors(const double*, RegressionRecord* record,
                  std::vector<Eigen::MatrixXd>* phi) const {
    YawRateRegressors(false, record, phi);
  }
  void Coefficients(const double* p, double* theta) const {
    theta[0] = p[1] / p[0];
    theta[1] = p[1] * p[2] / p[0];
    theta[2] = -1.0 / p[0];
  }
  int Region(const double*) const { return 0; }

  template <class T, class U>
  void Output(const T* x, const U* u, const T* p, T* y) const {
    y[0] = x[0];
    y[1] = x[1];
  }
};

struct Norrbin {
  static constexpr int kNumStates = 2;
  static constexpr int kMaxParameters = 4;  // T, K, alpha, delta_0
  static constexpr int kNumInputs = 1;
  static constexpr int kNumOutputs = 2;

  ModelInfo Info() const {
    return WithParameterUnits({"nomoto_norrbin",
                               {"psi", "r"},
                               {"delta"},
                               {"psi", "r"},
                               {"T", "K", "alpha", "delta_0"},
                               {10.0, 0.1, 0.0, 0.0},
                               {true, false},
                               {},
                               {},
                               {"rad", "rad/s"},
                               {"rad", "rad/s"},
                               {"rad"}},
                              {"s", "1/s", "s^2/rad^2", "rad"});
  }

  template <class T, class U>
  bool operator()(const T* x, const U* u, const T* p, T* xdot) const {
    const T& time_constant = p[0];
    if (!(time_constant > 0.0)) return false;
    const T& r = x[1];
    xdot[0] = r;
    xdot[1] = (p[1] * (u[0] + p[3]) - r - p[2] * r * r * r) / time_constant;
    return true;
  }

  void GuessState(const double* y, const double* ydot, double* x) const {
    GuessYawRate(y, ydot, x);
  }

  RegressionForm Regression() const { return YawRateRegression(true); }
  void Regressors(const double*, RegressionRecord* record,
                  std::vector<Eigen::MatrixXd>* phi) const {
    YawRateRegressors(true, record, phi);
  }
  void Coefficients(const double* p, double* theta) const {
    theta[0] = p[1] / p[0];
    theta[1] = p[1] * p[3] / p[0];
    theta[2] = -1.0 / p[0];
    theta[3] = -p[2] / p[0];
  }
  int Region(const double*) const { return 0; }

  template <class T, class U>
  void Output(const T* x, const U* u, const T* p, T* y) const {
    y[0] = x[0];
    y[1] = x[1];
  }
};

struct SecondOrder {
  static constexpr int kNumStates = 3;  // psi, xi1, xi2
  static constexpr int kMaxParameters = 5;  // T1, T2, T3, K, delta_0
  static constexpr int kNumInputs = 1;
  static constexpr int kNumOutputs = 2;

  ModelInfo Info() const {
    ModelInfo info{"nomoto_second_order",
                   {"psi", "xi1", "xi2"},
                   {"delta"},
                   {"psi", "r"},
                   {"T1", "T2", "T3", "K", "delta_0"},
                   {20.0, 5.0, 5.0, 0.1, 0.0},
                   {true, false},
                   {{0, 1}},
                   {},
                   {"rad", "rad/s"},
                   {"rad", "rad", "rad/s"},  // xi1, xi2 carry the rudder angle's unit
                   {"rad"}};
    info.positive_parameters = {true, true, true, false, false};  // the time constants
    return WithParameterUnits(info, {"s", "s", "s", "1/s", "rad"});
  }

  template <class T, class U>
  bool operator()(const T* x, const U* u, const T* p, T* xdot) const {
    const T product = p[0] * p[1];
    if (!(product > 0.0)) return false;
    xdot[0] = p[3] * (x[1] + p[2] * x[2]);
    xdot[1] = x[2];
    xdot[2] = (u[0] + p[4] - x[1] - (p[0] + p[1]) * x[2]) / product;
    return true;
  }

  template <class T, class U>
  void Output(const T* x, const U* u, const T* p, T* y) const {
    y[0] = x[0];
    y[1] = p[3] * (x[1] + p[2] * x[2]);
  }
};

}  // namespace vesselid::nomoto

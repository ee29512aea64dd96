// Nomoto steering models that can be course-unstable (MODELS.md §2). Input: rudder angle
// delta [rad] and, with a ship length L configured, the speed U [m/s]. Outputs: heading psi
// [rad] and yaw rate r [rad/s].
//
// Norrbin's n1-form (type first_order_n1, norrbin_n1):
//
//   T r' + n1 r + n3 r^3 = K (delta + delta_0),   psi' = r      (first_order_n1: n3 = 0)
//
// n1 is free in sign: n1 > 0 a course-stable ship (n1 = 1 is Nomoto's T r' + r = K delta),
// n1 < 0 a course-unstable one (a large tanker): the linear yaw pole -n1/T is then positive
// and the spiral test's r(delta) curve has a hysteresis loop. T > 0 (the yaw inertia term),
// K of either sign (negative for the patrol craft's rudder convention). The equation may be
// divided by any positive number, so the data determine only K/T, n1/T and n3/T: a stage
// holds T (at a value from a similar hull) and estimates K, n1, n3; they scale with the held T.
//
// With a length L > 0 the parameters are non-dimensional and the speed is an input:
//   T = T_nd L/U,  K = K_nd U/L,  n3 = n3_nd (L/U)^2   (n1 is non-dimensional already), so
//   r' = s^2 K_nd/T_nd (delta + delta_0) - s n1/T_nd r - n3_nd/(s T_nd) r^3,   s = U/L,
// one set of parameters for runs at different speeds. U must be > 0: a record with a sample
// that is not is refused.
//
// Equation-error form (least-squares stage), theta = [K/T, K delta_0/T, -n1/T (, -n3/T)]
// on the regressors [s^2 delta, s^2, s r (, r^3/s)] (s = 1 without a length).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/model/model.h"
#include "engine/model/regression_form.h"
#include "problems/nomoto/nomoto_models.h"

namespace vesselid::nomoto {

struct N1Form {
  static constexpr int kNumStates = 2;   // psi, r
  static constexpr int kMaxParameters = 5;  // T, K, n1 (, n3), delta_0
  static constexpr int kNumInputs = 2;   // delta (, U with a length)
  static constexpr int kNumOutputs = 2;  // psi, r

  bool cubic = false;   // norrbin_n1
  double length = 0.0;  // L [m]; > 0: non-dimensional parameters and the speed input U

  bool speed() const { return length > 0.0; }
  int delta_0() const { return cubic ? 4 : 3; }  // parameter index of delta_0

  ModelInfo Info() const {
    ModelInfo info;
    info.name = std::string(cubic ? "nomoto_norrbin_n1" : "nomoto_first_order_n1") +
                (speed() ? "_speed" : "");
    info.states = {"psi", "r"};
    info.inputs = {"delta"};
    if (speed()) {
      info.inputs.push_back("U");
      info.positive_inputs = {false, true};
    }
    info.outputs = {"psi", "r"};
    const std::string nd = speed() ? "_nd" : "";
    info.parameters = {"T" + nd, "K" + nd, "n1"};
    // Typical values: a ship of T 100 s, K 0.05 1/s at n1 = 1 (non-dimensional 2.5 and 2).
    info.parameter_defaults =
        speed() ? std::vector<double>{2.5, 2.0, 1.0} : std::vector<double>{100.0, 0.05, 1.0};
    if (cubic) {
      info.parameters.push_back("n3" + nd);
      info.parameter_defaults.push_back(0.0);
    }
    info.parameters.push_back("delta_0");
    info.parameter_defaults.push_back(0.0);
    info.angle_outputs = {true, false};
    info.output_units = {"rad", "rad/s"};
    info.state_units = {"rad", "rad/s"};
    info.input_units = speed() ? std::vector<std::string>{"rad", "m/s"}
                               : std::vector<std::string>{"rad"};
    // Non-dimensional with a length: T' = T U/L, K' = K L/U, n3' = n3 (U/L)^2.
    std::vector<std::string> units = speed() ? std::vector<std::string>{"", "", ""}
                                             : std::vector<std::string>{"s", "1/s", ""};
    if (cubic) units.push_back(speed() ? "" : "s^2/rad^2");
    units.push_back("rad");
    return WithParameterUnits(info, units);
  }

  // s = U/L, or 1 without a length; NaN when the speed is not a positive number.
  template <class U>
  U SpeedRatio(const U* u) const {
    if (!speed()) return U(1.0);
    return u[1] > 0.0 ? U(u[1] / length) : U(std::nan(""));
  }

  template <class T, class U>
  bool operator()(const T* x, const U* u, const T* p, T* xdot) const {
    const T& time_constant = p[0];
    using std::isfinite;
    const U s = SpeedRatio(u);
    if (!(time_constant > 0.0) || !isfinite(s)) return false;
    const T& r = x[1];
    xdot[0] = r;
    T rate = s * s * p[1] * (u[0] + p[delta_0()]) - s * p[2] * r;
    if (cubic) rate -= p[3] * r * r * r / s;
    xdot[1] = rate / time_constant;
    return true;
  }

  template <class T, class U>
  void Output(const T* x, const U*, const T*, T* y) const {
    y[0] = x[0];
    y[1] = x[1];
  }

  void GuessState(const double* y, const double* ydot, double* x) const {
    GuessYawRate(y, ydot, x);
  }

  RegressionForm Regression() const {
    RegressionForm form;
    form.states = {1};
    const std::string nd = speed() ? "_nd" : "";
    const std::string t = "/T" + nd;
    form.coefficients = {{"K" + nd + t, "K" + nd + "*delta_0" + t, "-n1" + t}};
    if (cubic) form.coefficients[0].push_back("-n3" + nd + t);
    form.regions = {"all"};
    return form;
  }

  void Regressors(const double*, RegressionRecord* record,
                  std::vector<Eigen::MatrixXd>* phi) const {
    const int n = record->size();
    phi->assign(1, Eigen::MatrixXd(n, cubic ? 4 : 3));
    Eigen::MatrixXd& m = (*phi)[0];
    for (int k = 0; k < n; ++k) {
      const double speed_now = speed() ? record->u(k, 1) : 0.0;
      const double s = !speed() ? 1.0 : speed_now > 0.0 ? speed_now / length : std::nan("");
      const double r = record->x(k, 1);
      m.row(k).head<3>() << s * s * record->u(k, 0), s * s, s * r;
      if (cubic) m(k, 3) = r * r * r / s;
    }
  }

  void Coefficients(const double* p, double* theta) const {
    theta[0] = p[1] / p[0];
    theta[1] = p[1] * p[delta_0()] / p[0];
    theta[2] = -p[2] / p[0];
    if (cubic) theta[3] = -p[3] / p[0];
  }

  int Region(const double*) const { return 0; }
};

}  // namespace vesselid::nomoto

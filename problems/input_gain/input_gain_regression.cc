// Equation-error form of the input-gain model (see input_gain_model.h).
#include <cmath>

#include "problems/input_gain/input_gain_model.h"

namespace vesselid::input_gain {
namespace {

constexpr const char* kEquation[3] = {"u", "v", "r"};

// s+, s+^2, s-, s-^2 of one PWM value about the dead zone [d_r, d_f].
std::array<double, kPropellerColumns> PropellerSignals(double x, double d_f, double d_r) {
  const double plus = x > d_f ? x - d_f : 0.0;
  const double minus = x < d_r ? x - d_r : 0.0;
  return {plus, plus * plus, minus, minus * minus};
}

// Which of s+, s+^2, s-, s-^2 the thrust law's terms make regressor columns.
std::vector<int> PropellerColumns(const ThrustLaw& law) {
  std::vector<int> columns;
  if (law.linear) columns.push_back(0);
  if (law.quadratic) columns.push_back(1);
  if (law.linear) columns.push_back(2);
  if (law.quadratic) columns.push_back(3);
  return columns;
}

}  // namespace

template <bool kDynamic>
RegressionForm InputGainModel<kDynamic>::Regression() const {
  RegressionForm form;
  form.states = {3, 4, 5};
  const char* gain[3] = {"b_u", "b_v", "b_r"};
  for (int i = 0; i < 3; ++i) {
    std::vector<std::string> names;
    for (int term : bases_.terms[i]) names.push_back(std::string(kEquation[i]) + "." + TermNames()[term]);
    const std::string b = gain[i];
    // The ahead term that carries the scale has coefficient b itself (thrust_law.h).
    const std::string names_of[kPropellerColumns] = {b, law_.linear ? b + "*k_f" : b, b + "*k_r1",
                                                     "-" + b + "*k_r2"};
    for (int column : PropellerColumns(law_)) names.push_back(names_of[column]);
    form.coefficients.push_back(names);
  }
  const int prop = PropellerIndex();
  if (law_.dead_zone) form.profiled = {prop + thrust_.d_f, prop + thrust_.d_r};
  if (kDynamic) form.profiled.push_back(prop + thrust_.tau_T);
  form.regions = {"ff", "fr", "rf", "rr"};
  return form;
}

template <bool kDynamic>
void InputGainModel<kDynamic>::Regressors(const double* p, RegressionRecord* record,
                                          std::vector<Eigen::MatrixXd>* phi) const {
  const double* prop = p + PropellerIndex();
  const int rows = record->size();
  // Discrete first-order filter of the thrust (a = 0: static propellers).
  const double a = kDynamic ? std::exp(-record->dt / prop[thrust_.tau_T]) : 0.0;
  const double d_f = law_.dead_zone ? prop[thrust_.d_f] : 0.0;
  const double d_r = law_.dead_zone ? prop[thrust_.d_r] : 0.0;
  const std::vector<int> columns = PropellerColumns(law_);
  std::array<double, kPropellerColumns> left{}, right{};
  phi->resize(3);
  for (int i = 0; i < 3; ++i) {
    (*phi)[i].resize(rows, static_cast<int>(bases_.terms[i].size() + columns.size()));
  }
  for (int k = 0; k < rows; ++k) {
    // Dynamic: the filter state at k is driven by the inputs up to k - 1 (held over each
    // grid interval), started at steady state. Static: the thrust of the input at k.
    const auto target_left = PropellerSignals(record->u(k, 0), d_f, d_r);
    const auto target_right = PropellerSignals(record->u(k, 1), d_f, d_r);
    if (k == 0 || !kDynamic) {
      left = target_left;
      right = target_right;
    }
    const double u = record->x(k, 3), v = record->x(k, 4), r = record->x(k, 5);
    for (int i = 0; i < 3; ++i) {
      Eigen::MatrixXd& m = (*phi)[i];
      const std::vector<int>& terms = bases_.terms[i];
      for (size_t j = 0; j < terms.size(); ++j) m(k, j) = TermValue(terms[j], u, v, r);
      const double sign = i == 0 ? 1.0 : -1.0;
      for (size_t j = 0; j < columns.size(); ++j) {
        m(k, terms.size() + j) = left[columns[j]] + sign * right[columns[j]];
      }
    }
    if constexpr (kDynamic) {
      // T = s+ + k_f s+^2 + k_r1 s- - k_r2 s-^2 of the filtered signals (the law's terms).
      auto thrust = [&](const std::array<double, kPropellerColumns>& s) {
        double t = 0.0;
        if (law_.linear) t += s[0] + prop[thrust_.k_r1] * s[2];
        if (law_.quadratic) {
          t += (law_.linear ? prop[thrust_.k_f] : 1.0) * s[1] - prop[thrust_.k_r2] * s[3];
        }
        return t;
      };
      record->x(k, 6) = thrust(left);
      record->x(k, 7) = thrust(right);
    }
    for (int j = 0; j < kPropellerColumns; ++j) {
      left[j] = a * left[j] + (1.0 - a) * target_left[j];
      right[j] = a * right[j] + (1.0 - a) * target_right[j];
    }
  }
}

template <bool kDynamic>
void InputGainModel<kDynamic>::Coefficients(const double* p, double* theta) const {
  const double* gain = p + gains_;
  const double* prop = p + PropellerIndex();
  const std::vector<int> columns = PropellerColumns(law_);
  int out = 0;
  for (int i = 0; i < 3; ++i) {
    for (size_t j = 0; j < bases_.terms[i].size(); ++j) theta[out++] = p[first_[i] + j];
    for (int column : columns) {
      switch (column) {
        case 0:
          theta[out++] = gain[i];
          break;
        case 1:
          theta[out++] = law_.linear ? gain[i] * prop[thrust_.k_f] : gain[i];
          break;
        case 2:
          theta[out++] = gain[i] * prop[thrust_.k_r1];
          break;
        default:
          theta[out++] = -gain[i] * prop[thrust_.k_r2];
          break;
      }
    }
  }
}

template class InputGainModel<false>;
template class InputGainModel<true>;

}  // namespace vesselid::input_gain

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
    names.insert(names.end(), {b, b + "*k_f", b + "*k_r1", "-" + b + "*k_r2"});
    form.coefficients.push_back(names);
  }
  const int prop = PropellerIndex();
  form.profiled = {prop + 3, prop + 4};
  if (kDynamic) form.profiled.push_back(prop + 5);
  form.regions = {"ff", "fr", "rf", "rr"};
  return form;
}

template <bool kDynamic>
void InputGainModel<kDynamic>::Regressors(const double* p, RegressionRecord* record,
                                          std::vector<Eigen::MatrixXd>* phi) const {
  const double* prop = p + PropellerIndex();
  const int rows = record->size();
  // Discrete first-order filter of the thrust (a = 0: static propellers).
  const double a = kDynamic ? std::exp(-record->dt / prop[5]) : 0.0;
  std::array<double, kPropellerColumns> left{}, right{};
  phi->resize(3);
  for (int i = 0; i < 3; ++i) {
    (*phi)[i].resize(rows, static_cast<int>(bases_.terms[i].size()) + kPropellerColumns);
  }
  for (int k = 0; k < rows; ++k) {
    // Dynamic: the filter state at k is driven by the inputs up to k - 1 (held over each
    // grid interval), started at steady state. Static: the thrust of the input at k.
    const auto target_left = PropellerSignals(record->u(k, 0), prop[3], prop[4]);
    const auto target_right = PropellerSignals(record->u(k, 1), prop[3], prop[4]);
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
      for (int j = 0; j < kPropellerColumns; ++j) {
        m(k, terms.size() + j) = left[j] + sign * right[j];
      }
    }
    if constexpr (kDynamic) {
      // T = s+ + k_f s+^2 + k_r1 s- - k_r2 s-^2 of the filtered signals.
      auto thrust = [&](const std::array<double, kPropellerColumns>& s) {
        return s[0] + prop[0] * s[1] + prop[1] * s[2] - prop[2] * s[3];
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
  int out = 0;
  for (int i = 0; i < 3; ++i) {
    for (size_t j = 0; j < bases_.terms[i].size(); ++j) theta[out++] = p[first_[i] + j];
    theta[out++] = gain[i];
    theta[out++] = gain[i] * prop[0];
    theta[out++] = gain[i] * prop[1];
    theta[out++] = -gain[i] * prop[2];
  }
}

template class InputGainModel<false>;
template class InputGainModel<true>;

}  // namespace vesselid::input_gain

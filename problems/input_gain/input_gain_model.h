// Joint input-gain model of a twin-propeller catamaran (MODELS.md §3, seed 000).
//
//   n' = u cos psi - v sin psi,  e' = u sin psi + v cos psi,  psi' = r
//   u' = f_u(nu) + b_u (T_L + T_R)
//   v' = f_v(nu) + b_v (T_L - T_R)
//   r' = f_r(nu) + b_r (T_L - T_R)
//
// f_i(nu) = sum_k c_ik phi_k(nu) over a configured basis (basis.h). Propeller thrust from
// normalised PWM x (both propellers alike) by the configured thrust law (thrust_law.h); by
// default, with the dead zone [d_r, d_f]:
//   T_s(x) = s + k_f s^2,        s = x - d_f,   x > d_f
//   T_s(x) = k_r1 s - k_r2 s^2,  s = x - d_r,   x < d_r,   else 0
// (the forward linear coefficient is 1: the scale lives in the gains). Static variant:
// T_i = T_s(u_i). Dynamic variant: states T_L, T_R with T_i' = (T_s(u_i) - T_i) / tau_T.
//
// Parameters, in order: the coefficients "u.<term>", "v.<term>", "r.<term>" of the three
// bases, then b_u, b_v, b_r, those of the thrust law (k_f, k_r1, k_r2, d_f, d_r by default)
// and (dynamic) tau_T.
// Outputs n, e, psi (measured) and u, v, r (for velocity metrics; normally not measured).
//
// Equation-error form (regression_form.h): given the propeller parameters that enter the
// thrust nonlinearly (d_f, d_r, tau_T: profiled), each velocity equation is linear in
//   theta_u = [c_u..., b_u, b_u k_f, b_u k_r1, -b_u k_r2]
// with regressors [phi(nu)..., S1, S2, S3, S4], S_j the sum (surge) or difference (sway, yaw)
// over the propellers of s+, s+^2, s-, s-^2 (those of the configured terms), filtered like the
// thrust in the dynamic variant (T(k+1) = a T(k) + (1 - a) T_s(u(k)), a = exp(-dt / tau_T),
// seed 000 eq. 21).
#pragma once

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/model/model.h"
#include "engine/model/regression_form.h"
#include "problems/input_gain/basis.h"
#include "problems/input_gain/thrust_law.h"

namespace vesselid::input_gain {

// Terms of the surge, sway and yaw bases (indices into Term).
struct Bases {
  std::array<std::vector<int>, 3> terms = {
      std::vector<int>{kTermOne, kTermU, kTermAbsUU, kTermVR, kTermRR},
      std::vector<int>{kTermOne, kTermV, kTermR, kTermAbsVV, kTermUR, kTermUV},
      std::vector<int>{kTermOne, kTermV, kTermR, kTermAbsRR, kTermUV, kTermUR}};
};

// Operating regions of seed 000 eq. 20 by the sign of the PWM of (left, right).
enum Region { kForwardForward, kForwardReverse, kReverseForward, kReverseReverse };

// Propeller signals of one equation's regressors: sums or differences of s+, s+^2, s-, s-^2
// over the two propellers (those of the thrust law's terms become columns).
constexpr int kPropellerColumns = 4;

template <bool kDynamic>
class InputGainModel {
 public:
  static constexpr int kNumStates = kDynamic ? 8 : 6;
  static constexpr int kNumInputs = 2;   // u_L, u_R
  static constexpr int kNumOutputs = 6;  // n, e, psi, u, v, r

  explicit InputGainModel(Bases bases = Bases(), ThrustLaw law = ThrustLaw())
      : bases_(std::move(bases)), law_(law), thrust_(law, kDynamic) {
    int offset = 0;
    for (int i = 0; i < 3; ++i) {
      first_[i] = offset;
      offset += static_cast<int>(bases_.terms[i].size());
    }
    gains_ = offset;
  }

  const Bases& bases() const { return bases_; }
  const ThrustLaw& thrust_law() const { return law_; }
  const ThrustOffsets& thrust_offsets() const { return thrust_; }  // from PropellerIndex()
  int GainIndex() const { return gains_; }          // b_u, b_v, b_r
  int PropellerIndex() const { return gains_ + 3; }  // the thrust law's, then tau_T

  ModelInfo Info() const {
    ModelInfo info;
    info.name = kDynamic ? "input_gain_dynamic" : "input_gain_static";
    info.states = {"n", "e", "psi", "u", "v", "r"};
    if (kDynamic) info.states.insert(info.states.end(), {"T_L", "T_R"});
    info.inputs = {"u_L", "u_R"};
    info.outputs = {"n", "e", "psi", "u", "v", "r"};
    const char* equation[3] = {"u", "v", "r"};
    for (int i = 0; i < 3; ++i) {
      for (int term : bases_.terms[i]) {
        info.parameters.push_back(std::string(equation[i]) + "." + TermNames()[term]);
        // Linear damping of each component starts negative (stable), the rest at 0.
        const bool damping = (i == 0 && term == kTermU) || (i == 1 && term == kTermV) ||
                             (i == 2 && term == kTermR);
        info.parameter_defaults.push_back(damping ? -0.5 : 0.0);
      }
    }
    info.parameters.insert(info.parameters.end(), {"b_u", "b_v", "b_r"});
    info.parameter_defaults.insert(info.parameter_defaults.end(), {0.5, 0.0, 1.0});
    auto add = [&](int offset, const char* name, double value) {
      if (offset < 0) return;
      info.parameters.push_back(name);
      info.parameter_defaults.push_back(value);
    };
    add(thrust_.k_f, "k_f", 0.5);
    add(thrust_.k_r1, "k_r1", 1.0);
    add(thrust_.k_r2, "k_r2", law_.linear ? 0.0 : 0.5);  // alone: astern thrust at the start
    add(thrust_.d_f, "d_f", 0.0);
    add(thrust_.d_r, "d_r", 0.0);
    add(thrust_.tau_T, "tau_T", 0.3);
    // The linear term carries the scale with the gains: fitted to a purely quadratic
    // thruster, k_f grows and b_u, b_v, b_r shrink together.
    if (thrust_.k_f >= 0) {
      info.compensation_hints["k_f"] =
          "the thrust may have no linear term: try thrust: [\"n|n|\"] (or fix k_f)";
    }
    if (law_.dead_zone) {
      info.compensation_hints["d_f"] = info.compensation_hints["d_r"] =
          "a dead zone at its bound stands in for a thrust law the model lacks: try thrust: "
          "[\"n|n|\"] or dead_zone: false";
    }
    info.angle_outputs = {false, false, true, false, false, false};
    info.output_units = {"m", "m", "rad", "m/s", "m/s", "rad/s"};
    return info;
  }

  // T_s(x) of the configured law (thrust_law.h); p: all parameters.
  template <class T, class U>
  T StaticThrust(const U& x, const T* p) const {
    const T* prop = p + PropellerIndex();
    const T zero(0.0);
    const T d_f = law_.dead_zone ? prop[thrust_.d_f] : zero;
    const T d_r = law_.dead_zone ? prop[thrust_.d_r] : zero;
    if (x > d_f) {
      const T s = x - d_f;
      if (!law_.quadratic) return s;
      if (!law_.linear) return s * s;
      return s + prop[thrust_.k_f] * s * s;
    }
    if (x < d_r) {
      const T s = x - d_r;
      T thrust = zero;
      if (law_.linear) thrust += prop[thrust_.k_r1] * s;
      if (law_.quadratic) thrust -= prop[thrust_.k_r2] * s * s;
      return thrust;
    }
    return zero;
  }

  template <class T, class U>
  bool operator()(const T* x, const U* in, const T* p, T* xdot) const {
    using std::cos;
    using std::sin;
    const T& psi = x[2];
    const T& u = x[3];
    const T& v = x[4];
    const T& r = x[5];
    T thrust_left, thrust_right;
    if constexpr (kDynamic) {
      const T& tau = p[PropellerIndex() + thrust_.tau_T];
      if (!(tau > 0.0)) return false;
      thrust_left = x[6];
      thrust_right = x[7];
      xdot[6] = (StaticThrust(in[0], p) - thrust_left) / tau;
      xdot[7] = (StaticThrust(in[1], p) - thrust_right) / tau;
    } else {
      thrust_left = StaticThrust(in[0], p);
      thrust_right = StaticThrust(in[1], p);
    }
    const T c = cos(psi), s = sin(psi);
    xdot[0] = u * c - v * s;
    xdot[1] = u * s + v * c;
    xdot[2] = r;
    const T* gain = p + gains_;
    const T sum = thrust_left + thrust_right;
    const T difference = thrust_left - thrust_right;
    xdot[3] = Lumped(0, p, u, v, r) + gain[0] * sum;
    xdot[4] = Lumped(1, p, u, v, r) + gain[1] * difference;
    xdot[5] = Lumped(2, p, u, v, r) + gain[2] * difference;
    return IsFinite(xdot[3]) && IsFinite(xdot[4]) && IsFinite(xdot[5]);
  }

  template <class T, class U>
  void Output(const T* x, const U* u, const T* p, T* y) const {
    for (int i = 0; i < 6; ++i) y[i] = x[i];
  }

  // Body velocities from the position and heading rates: nu = R(psi)^T eta'.
  void GuessState(const double* y, const double* ydot, double* x) const {
    if (!std::isfinite(y[2])) return;
    const double c = std::cos(y[2]), s = std::sin(y[2]);
    if (std::isnan(y[3]) && std::isfinite(ydot[0]) && std::isfinite(ydot[1])) {
      x[3] = c * ydot[0] + s * ydot[1];
    }
    if (std::isnan(y[4]) && std::isfinite(ydot[0]) && std::isfinite(ydot[1])) {
      x[4] = -s * ydot[0] + c * ydot[1];
    }
    if (std::isnan(y[5]) && std::isfinite(ydot[2])) x[5] = ydot[2];
  }

  // Passive damping over the range the records cover: a velocity's own terms
  // f(x) = a x + b |x| x feed the motion where x f(x) = x^2 (a + b |x|) > 0, i.e. near 0 when
  // a > 0 and above |x| = -a / b when b > 0. With `state_limits` (the largest |u|, |v|, |r|
  // the records take the model to) judged up to there, else for every x.
  std::vector<std::string> Admissibility(const double* p, const double* state_limits) const {
    std::vector<std::string> problems;
    const double* prop = p + PropellerIndex();
    if (law_.dead_zone && prop[thrust_.d_r] > prop[thrust_.d_f]) {
      problems.push_back("dead zone d_r > d_f");
    }
    if (kDynamic && !(prop[thrust_.tau_T] > 0)) problems.push_back("tau_T must be > 0");
    if (state_limits != nullptr) ThrustMonotonicity(p, state_limits + kNumStates, &problems);
    const char* equation[3] = {"u", "v", "r"};
    const int own[3][2] = {{kTermU, kTermAbsUU}, {kTermV, kTermAbsVV}, {kTermR, kTermAbsRR}};
    for (int i = 0; i < 3; ++i) {
      double coefficient[2] = {0.0, 0.0};
      for (int k = 0; k < static_cast<int>(bases_.terms[i].size()); ++k) {
        for (int j = 0; j < 2; ++j) {
          if (bases_.terms[i][k] == own[i][j]) coefficient[j] = p[first_[i] + k];
        }
      }
      const double a = coefficient[0], b = coefficient[1];
      const double limit = state_limits != nullptr && std::isfinite(state_limits[3 + i])
                               ? state_limits[3 + i]
                               : std::numeric_limits<double>::infinity();
      char text[320];
      if (a > 0.0) {
        std::snprintf(text, sizeof(text),
                      "%s.%s = %+.4g > 0: linear damping of %s that feeds the motion (passive "
                      "damping is <= 0)",
                      equation[i], TermNames()[own[i][0]].c_str(), a, equation[i]);
        problems.push_back(text);
      } else if (b > 0.0 && a + b * limit > 0.0) {
        if (std::isinf(limit)) {
          std::snprintf(text, sizeof(text),
                        "%s.%s = %+.4g > 0: quadratic damping of %s that feeds the motion above "
                        "|%s| = %.4g (passive damping is <= 0)",
                        equation[i], TermNames()[own[i][1]].c_str(), b, equation[i],
                        equation[i], -a / b);
        } else {
          std::snprintf(text, sizeof(text),
                        "%s.%s = %+.4g > 0: the damping %+.4g %s %+.4g |%s|%s of %s feeds the "
                        "motion above |%s| = %.4g, and the records reach |%s| = %.4g",
                        equation[i], TermNames()[own[i][1]].c_str(), b, a, equation[i], b,
                        equation[i], equation[i], equation[i], equation[i], -a / b, equation[i],
                        limit);
        }
        problems.push_back(text);
      }
    }
    return problems;
  }

  // The thrust law T_s(x) must not fall as the command x rises, over the commands the records
  // give (`input_range`: min and max of each input, operating_range.h): an astern branch whose
  // sign changes (k_r1 < 0) has a harder reverse command push less astern, or ahead. Judged on a grid of 401
  // commands; a fall below 5 % of the thrust's span over the range (rounding of a branch's
  // start) is not counted.
  void ThrustMonotonicity(const double* p, const double* input_range,
                          std::vector<std::string>* problems) const {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (int i = 0; i < kNumInputs; ++i) {
      low = std::min(low, input_range[2 * i]);
      high = std::max(high, input_range[2 * i + 1]);
    }
    if (!(low < high) || !std::isfinite(low) || !std::isfinite(high)) return;
    constexpr int kPoints = 401;
    double t_min = std::numeric_limits<double>::infinity(), t_max = -t_min;
    double best = -std::numeric_limits<double>::infinity(), best_x = low;  // highest T so far
    double fall = 0.0, fall_from = low, fall_to = low;
    for (int k = 0; k < kPoints; ++k) {
      const double x = low + (high - low) * k / (kPoints - 1);
      const double thrust = StaticThrust(x, p);
      t_min = std::min(t_min, thrust);
      t_max = std::max(t_max, thrust);
      if (thrust > best) {
        best = thrust;
        best_x = x;
      } else if (best - thrust > fall) {
        fall = best - thrust;
        fall_from = best_x;
        fall_to = x;
      }
    }
    if (!(fall > kMonotoneTolerance * (t_max - t_min))) return;
    char text[320];
    std::snprintf(text, sizeof(text),
                  "the thrust law is not monotone in its command: T_s falls by %.3g (%.0f %% of "
                  "its span) from x = %.3g to x = %.3g as the command rises, within the commands the "
                  "records give "
                  "[%.3g, %.3g]",
                  fall, 100.0 * fall / (t_max - t_min), fall_from, fall_to, low, high);
    problems->push_back(text);
  }
  static constexpr double kMonotoneTolerance = 0.05;

  // A dead zone whose branch beyond it bends the wrong way: a propeller's thrust grows at
  // least linearly past its zone (ahead s + k_f s^2 with k_f >= 0; astern magnitude
  // k_r1 |s| + k_r2 s^2 with k_r1, k_r2 >= 0), so a zone with k_f < 0 (or k_r1, k_r2 < 0)
  // is the zone and the bend standing in for a law the model lacks (a purely quadratic
  // thruster's flat start). Judged for a zone edge wider than 1 % of the commands' span that
  // the commands reach past.
  std::vector<std::string> StructureDoubts(const double* p, const double* range) const {
    std::vector<std::string> doubts;
    if (!law_.dead_zone || !law_.linear || !law_.quadratic || range == nullptr) return doubts;
    const double* input = range + kNumStates;
    const double low = std::min(input[0], input[2]), high = std::max(input[1], input[3]);
    if (!(low < high)) return doubts;
    const double* prop = p + PropellerIndex();
    const double d_f = prop[thrust_.d_f], d_r = prop[thrust_.d_r];
    const double k_f = prop[thrust_.k_f], k_r1 = prop[thrust_.k_r1], k_r2 = prop[thrust_.k_r2];
    const double edge = 0.01 * (high - low);
    char text[400];
    if (d_f > edge && high > d_f && k_f < 0.0) {
      std::snprintf(text, sizeof(text),
                    "the dead zone edge d_f = %.3g comes with an ahead branch that bends down "
                    "beyond it (k_f = %.3g < 0): a propeller's thrust grows at least linearly "
                    "past its zone, so the zone and the bend stand in for a law the model lacks; "
                    "try thrust: [\"n|n|\"], dead_zone: false",
                    d_f, k_f);
      doubts.push_back(text);
    }
    if (-d_r > edge && low < d_r && (k_r1 < 0.0 || k_r2 < 0.0)) {
      std::snprintf(text, sizeof(text),
                    "the dead zone edge d_r = %.3g comes with an astern branch that bends the "
                    "wrong way beyond it (k_r1 = %.3g, k_r2 = %.3g; both >= 0 for a propeller): "
                    "the zone and the bend stand in for a law the model lacks; try thrust: "
                    "[\"n|n|\"], dead_zone: false",
                    d_r, k_r1, k_r2);
      doubts.push_back(text);
    }
    return doubts;
  }

  int Region(const double* in) const {
    const bool left = in[0] >= 0.0, right = in[1] >= 0.0;
    if (left && right) return kForwardForward;
    if (left) return kForwardReverse;
    if (right) return kReverseForward;
    return kReverseReverse;
  }

  RegressionForm Regression() const;
  void Regressors(const double* p, RegressionRecord* record,
                  std::vector<Eigen::MatrixXd>* phi) const;
  void Coefficients(const double* p, double* theta) const;

 private:
  template <class T>
  static bool IsFinite(const T& value) {
    using std::isfinite;
    return isfinite(value);
  }

  template <class T>
  T Lumped(int i, const T* p, const T& u, const T& v, const T& r) const {
    const std::vector<int>& terms = bases_.terms[i];
    const T* c = p + first_[i];
    T f(0.0);
    for (size_t k = 0; k < terms.size(); ++k) f += c[k] * TermValue(terms[k], u, v, r);
    return f;
  }

  Bases bases_;
  ThrustLaw law_;
  ThrustOffsets thrust_;
  std::array<int, 3> first_{};
  int gains_ = 0;
};

}  // namespace vesselid::input_gain

// Terms a ship model may lack, scored through the filter. A candidate term c_j phi_j(x, u) is
// added to the right-hand side of one state (a state the identified process noise acts on):
//
//   x_s' = f_s(x, u, p) + sum_{j: target_j = s} c_j phi_j(x, u),
//
// phi_j one of 1, z, z|z|, z^3, sign(z) (smoothed: z / sqrt(z^2 + 0.05^2)) of a signal z = (a velocity state or an input) / its scale. At
// c = 0 the model is the identified one. One filter run on Jets gives the innovations'
// likelihood's gradient g and Fisher information I with respect to the stage's free unknowns
// and the candidates' c at once, exactly: the innovations' sensitivity to a missing term is the
// term filtered through the filter's own closed loop (prediction, gain, update), which a
// regression of the innovations on the term itself does not see (innovation_structure.h).
//
// Per sample i, with a_i = nu_i / sqrt(S_i) and -log L_i = 1/2 (a_i^2 + log S_i):
//   g  = sum_i a_i da_i + 1/2 d(log S_i)
//   I  = sum_i da_i da_i' + 1/4 d(log S_i) d(log S_i)'      (E[nu^2] = S: the Fisher information)
// (filter_error_cost.h writes the same likelihood as Ceres residuals.)
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "Eigen/Core"
#include "ceres/jet.h"
#include "engine/model/kalman_filter.h"

namespace vesselid {

struct OmittedTerm {
  // Where the smoothed sign turns, in units of the signal's RMS: a dead band or backlash of a
  // few per cent of the rudder's travel steps like a sign; smooth, so that Jets see a slope.
  static constexpr double kSignWidth = 0.05;
  enum class Signal { kConstant, kState, kInput };
  int target = 0;  // the state whose derivative gets the term
  Signal signal = Signal::kConstant;
  int index = 0;   // the state or input
  int power = 0;   // 0: sign(z) smoothed, 1: z, 2: z|z|, 3: z^3 (a constant has none)
  double scale = 1.0;

  // phi(x, u); an input that is not finite (an optional input left unmapped) gives 0.
  template <class T, class U>
  T Value(const T* x, const U* u) const {
    using std::abs;
    if (signal == Signal::kConstant) return T(1.0);
    if (signal == Signal::kInput && !std::isfinite(ScalarPartOf(u[index]))) return T(0.0);
    const T z = signal == Signal::kState ? T(x[index] / scale) : T(u[index] / scale);
    if (power == 2) return z * abs(z);
    if (power == 3) return z * z * z;
    if (power == 0) {
      using std::sqrt;
      return z / sqrt(z * z + kSignWidth * kSignWidth);
    }
    return z;
  }

 private:
  static double ScalarPartOf(double v) { return v; }
  template <class J>
  static double ScalarPartOf(const J& v) {
    return v.a;
  }
};

// The model with the terms added: parameters p[0, num_parameters) are the model's, the next
// terms.size() are the c_j.
template <class Model>
class ProbedModel {
 public:
  static constexpr int kNumStates = Model::kNumStates;
  static constexpr int kNumInputs = Model::kNumInputs;
  static constexpr int kNumOutputs = Model::kNumOutputs;

  ProbedModel(const Model& model, const std::vector<OmittedTerm>* terms, int num_parameters)
      : model_(model), terms_(terms), num_parameters_(num_parameters) {}

  template <class T, class U>
  bool operator()(const T* x, const U* u, const T* p, T* xdot) const {
    if (!model_(x, u, p, xdot)) return false;
    const T* c = p + num_parameters_;
    for (size_t j = 0; j < terms_->size(); ++j) {
      const OmittedTerm& term = (*terms_)[j];
      xdot[term.target] += c[j] * term.Value(x, u);
    }
    return true;
  }
  template <class T, class U>
  void Output(const T* x, const U* u, const T* p, T* y) const {
    model_.Output(x, u, p, y);
  }

 private:
  const Model& model_;
  const std::vector<OmittedTerm>* terms_;
  int num_parameters_ = 0;
};

// g and I over the chosen directions.
struct OmittedTermScore {
  Eigen::VectorXd gradient;
  Eigen::MatrixXd information;
  int samples = 0;
};

// Jet width of the probe's filter passes (one instantiation per model; more directions run
// in several passes).
inline constexpr int kOmittedTermJetSize = 16;

// Bytes the per-sample derivatives of a several-pass score may take; beyond, no score (the
// test is left out and says so).
inline constexpr double kOmittedTermMemory = 256.0 * 1024 * 1024;

// Whether a score over `directions` unknowns on `samples` samples would exceed that memory:
// several passes keep each sample's derivatives until the last (2 x samples x d doubles); one
// pass sums them as they come.
inline bool OmittedTermScoreExceedsMemory(int samples, int directions) {
  return directions > kOmittedTermJetSize &&
         16.0 * samples * directions > kOmittedTermMemory;
}

// The score of experiment e at the model's parameters p (num_parameters), initial state x0,
// disturbance theta, all candidates at c = 0, over `directions`: indices into the unknowns
// [p (num_parameters), x0 (kNumStates), theta (layout.size()), c (terms.size())]. False if the
// filter diverges, a figure is not finite, or the derivatives would take more than
// kOmittedTermMemory.
template <class Model>
bool ScoreOmittedTerms(const Model& model, const Experiment& e, const double* p,
                       int num_parameters, const double* x0, const double* p0,
                       const DisturbanceLayout& layout, const double* theta,
                       const std::vector<OmittedTerm>& terms, const std::vector<int>& directions,
                       OmittedTermScore* out) {
  using J = ceres::Jet<double, kOmittedTermJetSize>;
  constexpr int n = Model::kNumStates;
  const int np = num_parameters, nt = layout.size(), m = static_cast<int>(terms.size());
  const int d = static_cast<int>(directions.size());
  const int samples = e.num_samples();
  const int passes = std::max(1, (d + kOmittedTermJetSize - 1) / kOmittedTermJetSize);
  if (OmittedTermScoreExceedsMemory(samples, d)) return false;
  const ProbedModel<Model> probed(model, &terms, np);
  Eigen::VectorXd a(samples);
  Eigen::MatrixXd da(passes > 1 ? samples : 0, d), dlog(passes > 1 ? samples : 0, d);
  out->gradient = Eigen::VectorXd::Zero(d);
  out->information = Eigen::MatrixXd::Zero(d, d);
  Eigen::VectorXd row_a(d), row_log(d);
  std::vector<J> pj(np + m), thetaj(nt);
  std::array<J, n> xj;
  for (int first = 0; first < d || first == 0; first += kOmittedTermJetSize) {
    for (int i = 0; i < np; ++i) pj[i] = J(p[i]);
    for (int j = 0; j < m; ++j) pj[np + j] = J(0.0);
    for (int i = 0; i < n; ++i) xj[i] = J(x0[i]);
    for (int i = 0; i < nt; ++i) thetaj[i] = J(theta[i]);
    const int width = std::min(kOmittedTermJetSize, d - first);
    for (int k = 0; k < width; ++k) {
      const int u = directions[first + k];
      J* target = u < np ? &pj[u]
                  : u < np + n ? &xj[u - np]
                  : u < np + n + nt ? &thetaj[u - np - n]
                                    : &pj[np + (u - np - n - nt)];
      target->v[k] = 1.0;
    }
    bool finite = true;
    auto visit = [&](int i, const J& nu, const J& S) {
      using std::log;
      using std::sqrt;
      const J ai = nu / sqrt(S);
      const J li = log(S);
      a[i] = ai.a;
      finite = finite && std::isfinite(ai.a);
      if (passes > 1) {
        for (int k = 0; k < width; ++k) {
          da(i, first + k) = ai.v[k];
          dlog(i, first + k) = li.v[k];
        }
        return;
      }
      for (int k = 0; k < width; ++k) {
        row_a[k] = ai.v[k];
        row_log[k] = li.v[k];
      }
      out->gradient += ai.a * row_a + 0.5 * row_log;
      out->information.selfadjointView<Eigen::Lower>().rankUpdate(row_a);
      out->information.selfadjointView<Eigen::Lower>().rankUpdate(row_log, 0.25);
    };
    auto node = [](int, const J*, const double*) {};
    if (!RunKalmanFilter(probed, e, layout, pj.data(), xj.data(), p0, thetaj.data(), visit,
                         node) ||
        !finite) {
      return false;
    }
    if (d == 0) break;
  }
  out->samples = samples;
  if (passes > 1) {
    out->gradient = da.transpose() * a + 0.5 * dlog.colwise().sum().transpose();
    out->information = da.transpose() * da + 0.25 * dlog.transpose() * dlog;
  } else {
    out->information = out->information.selfadjointView<Eigen::Lower>();
  }
  return out->gradient.allFinite() && out->information.allFinite();
}

}  // namespace vesselid

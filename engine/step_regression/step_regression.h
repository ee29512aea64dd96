// Seed 004's identification of a damping-inertia model (§3.4) from its step samples
// (step_samples.h): each term sigma_U, sigma_r, m_U, m_r is regressed on its own sample set,
//
//   normalised:  x~ = (x - mean_x) / sd_x per state, y~ = (y - mean_y) / sd_y, per set
//   lasso:       min (1/N) sum W_ii (y~_i - phi(x~_i)^T b)^2 + lambda |b|_1 (intercept free)
//   lambda:      leave-one-group-out cross-validation over a path (lasso.h)
//   inertia:     phi_M = [phi, tanh(a~ (x~_s - b~))], (a, b) on a grid, the pair with the lowest
//                cross-validated error (at its best lambda) kept
//
// and the normalised polynomial is expanded exactly into the model's basis in x / scale
// (a = a~ / sd_s, b = mean_s + sd_s b~ for the asymptotic term), so that the estimate is the
// model's own parameter vector and can start an output-error refinement.
#pragma once

#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/model/damping_inertia_form.h"
#include "engine/regression/group_bootstrap.h"
#include "engine/regression/lasso.h"
#include "engine/step_regression/step_samples.h"

namespace vesselid {

struct StepRegressionOptions {
  StepSampleOptions samples;
  LassoOptions lasso;
  // Asymptotic inertia term: a on this grid (1 / unit of x_s, e.g. s/m), b on `b_points`
  // values spanning the inertia samples' range of x_s.
  std::vector<double> asymptote_a = {0.25, 0.5, 1.0, 2.0, 4.0};
  int asymptote_b_points = 13;
  // Bootstrap over the CV groups (step_regression_bootstrap.h); runs 0: none.
  GroupBootstrapOptions bootstrap{200};

  bool IsValid(const DampingInertiaForm& form, std::string* error) const;
};

// One regressed term (sigma_i or m_i).
struct TermRegression {
  std::string name;
  int samples = 0, groups = 0;
  double mean_x[2] = {0, 0}, sd_x[2] = {1, 1};  // normalisation of the states
  double mean_y = 0.0, sd_y = 1.0;              // and of the target
  LassoPath path;                               // at the chosen (a, b) for inertia terms
  double lambda = 0.0;                          // chosen
  Eigen::VectorXd normalised;                   // coefficients on the normalised basis
  double a = 0.0, b = 0.0;                      // asymptote (physical); inertia terms only
  struct AsymptoteCv {
    double a, b, cv_error, lambda;
  };
  std::vector<AsymptoteCv> asymptote_grid;      // cross-validation surface over (a, b)
  std::vector<double> coefficients;             // the model's (form.damping/inertia order)
  double r2 = 0.0, rms = 0.0;                   // on the samples, physical units, weighted
  double seconds = 0.0;
};

struct StepRegressionReport {
  StepSamples samples;
  std::vector<TermRegression> terms;  // sigma_0, sigma_1, m_0, m_1
  double normalisation_seconds = 0.0;
  double regression_seconds = 0.0;
};

// Extracts the samples and regresses every term. False with a message when a set has too
// few samples or groups for its regression.
bool RunStepRegression(const DampingInertiaForm& form,
                       const std::vector<RegressionRecord>& records,
                       const StepRegressionOptions& options, StepRegressionReport* report,
                       std::string* error);

// Writes the estimate into a full model parameter vector (form parameters only).
void StoreStepRegression(const DampingInertiaForm& form, const StepRegressionReport& report,
                         std::vector<double>* parameters);

// c with phi(x / scale)^T c = mean_y + sd_y phi((x - mean_x) / sd_x)^T b for every x: the
// normalised polynomial expanded into the model's basis (exact; solved on a grid of points).
std::vector<double> ExpandToModelBasis(int degree, const double* scale, const double* mean_x,
                                       const double* sd_x, double mean_y, double sd_y,
                                       const Eigen::VectorXd& b);

}  // namespace vesselid

// The regression of one term of a step regression (step_regression.h) on its sample set, for
// RunStepRegression and its bootstrap (step_regression_bootstrap.h).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/model/damping_inertia_form.h"
#include "engine/step_regression/step_regression.h"

namespace vesselid {

// One term's sample set, before normalisation.
struct SampleSet {
  std::vector<std::array<double, 2>> x;
  std::vector<double> y, w;
  std::vector<int> group;
};

// The sets of sigma_0, sigma_1 (the damping samples) and m_0, m_1 (each state's steps).
std::array<SampleSet, 4> TermSampleSets(const StepSamples& samples);

// Means and standard deviations of the set's states and target into *term.
void Normalise(const SampleSet& set, TermRegression* term);

// Normalised regressors: the polynomial basis in the term's normalised states, then (with
// `asymptote`) tanh(a_n (z_s - b_n)).
Eigen::MatrixXd Regressors(int degree, const SampleSet& set, const TermRegression& term,
                           bool asymptote, int asymptote_state, double a_n, double b_n);

// The normalised target and weights of the set, and the lasso options of a term with
// `columns` regressors (the intercept, column 0, unpenalised).
void NormalisedTarget(const SampleSet& set, const TermRegression& term, Eigen::VectorXd* y,
                      Eigen::VectorXd* w);
LassoOptions TermLassoOptions(const StepRegressionOptions& options, int columns);

// Lasso path with leave-one-group-out CV (and, for inertia terms, the (a, b) grid), the fit,
// and its expansion into the model basis; term->name and the normalisation must be set.
bool RegressTerm(const DampingInertiaForm& form, const SampleSet& set, bool inertia,
                 const StepRegressionOptions& options, TermRegression* term,
                 std::string* error);

}  // namespace vesselid

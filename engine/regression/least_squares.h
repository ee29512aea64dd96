// The least-squares stage (seed 000's procedure, generic): equation-error regression of each
// regressed state's derivative on the model's regressors (regression_form.h), then the model
// parameters from the regression coefficients by minimum distance:
//
//   1. profiled parameters (entering the regressors: a time constant, a dead zone) are
//      searched with NLopt (BOBYQA, within their bounds) on the concentrated likelihood
//      sum_i n_i log(RSS_i / n_i) of plain regressions: one value for all equations
//      (seed 000 eq. 41 asks one tau for the three velocities);
//   2. each equation is regressed on its samples (its operating regions, the selected
//      samples), with the stage's robust weighting and penalty (linear_regression.h);
//      coefficients depending only on held parameters move to the left-hand side, all-zero
//      columns (a region without reverse thrust) are dropped as not identified;
//   3. the free parameters p minimise sum_i |L_i^-1 (theta_i(p) - theta_i^)|^2, L_i L_i^T the
//      coefficient covariance of equation i: products such as b_u k_f, b_v k_f, b_r k_f give
//      one k_f, weighted by their precision. Cov(p) = (J^T J)^-1 at the minimum.
#pragma once

#include <string>
#include <vector>

#include "Eigen/Dense"
#include "engine/model/model_handle.h"
#include "engine/model/regression_form.h"
#include "engine/regression/group_bootstrap.h"
#include "engine/regression/group_bootstrap.h"
#include "engine/regression/linear_regression.h"
#include "engine/solve/metrics.h"
#include "engine/solve/parameter.h"

namespace vesselid {

struct LeastSquaresOptions {
  RegressionOptions regression;
  // Per equation (regressed state order): operating regions (RegressionForm::regions
  // indices) whose samples it is fitted on; empty: every sample.
  std::vector<std::vector<int>> regions;
  int max_profile_evaluations = 150;
  // Bootstrap of the estimates (least_squares_bootstrap.h); runs 0: none.
  GroupBootstrapOptions bootstrap;
  // Set by the bootstrap for one replicate: per record, per sample, how often the sample
  // enters the regressions (its block's draw count; empty: once each), and per equation the
  // penalty's lambda held at the full fit's value (empty: `regression.lambda`).
  std::vector<std::vector<int>> sample_counts;
  std::vector<double> equation_lambda;
};

struct EquationSummary {
  std::string state;
  int samples = 0;
  int rejected = 0;
  double lambda = 0.0;
  double r2 = 0.0;  // of the derivative (equation error), kept samples
  double residual_rms = 0.0;
  std::vector<std::string> coefficients;
  Eigen::VectorXd theta;       // NaN where not identified or held
  Eigen::VectorXd std_errors;  // NaN where unknown
  std::vector<bool> regressed;  // per coefficient: fitted (not held, not dropped)
};

struct LeastSquaresSummary {
  bool usable = false;
  std::string message;
  std::vector<EquationSummary> equations;
  int profile_evaluations = 0;
  double objective = 0.0;  // sum_i n_i log(RSS_i / n_i) at the profiled optimum
  std::vector<std::string> notes;
  double time_seconds = 0.0;

  std::string BriefReport() const;
};

// A per-experiment parameter's value for one experiment (regression record name).
struct ExperimentValue {
  int parameter = 0;  // model parameter index
  std::string experiment;
  double value = 0.0;
  double std_error = 0.0;  // NaN when undetermined
  bool undetermined = false;
};

struct LeastSquaresResult {
  // Every model parameter (held ones at their start; a per-experiment one at its mean).
  std::vector<double> values;
  std::vector<double> std_errors;  // NaN for held and undetermined parameters
  std::vector<bool> undetermined;
  std::vector<int> free;           // indices of the estimated parameters
  Eigen::MatrixXd covariance;      // of `free`
  std::vector<ExperimentValue> per_experiment;  // parameter by parameter, experiment order
};

// `specs` holds every model parameter in model order (ParameterRole kFixed: held; kFree,
// kIsolated, kShared: estimated; kPerExperiment: estimated for each experiment, i.e. each
// distinct record name: the coefficients it enters get one column per experiment, such as a
// rudder bias's intercept K delta_0/T, and the minimum distance finds one value per
// experiment). Records keep the internal states the model fills in (e.g. propeller thrusts)
// at the final values.
bool RunLeastSquares(const ModelHandle& model, const std::vector<ParameterSpec>& specs,
                     const LeastSquaresOptions& options, std::vector<RegressionRecord>* records,
                     LeastSquaresResult* result, LeastSquaresSummary* summary);

// One-step-ahead prediction of each regressed state (seed 000's validation metric):
//   x^(k+1) = x(k) + dt phi(k) theta(p),  compared with x(k+1) from the data,
// at the selected samples k in the equation's regions. One ChannelMetrics per state, named
// `label`.
bool OneStepMetrics(const ModelHandle& model, const std::vector<double>& p,
                    const LeastSquaresOptions& options, std::vector<RegressionRecord>* records,
                    const std::string& label, std::vector<ChannelMetrics>* metrics,
                    std::string* error);

}  // namespace vesselid

#include "engine/run/least_squares_stage.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "engine/regression/least_squares_bootstrap.h"

namespace vesselid {

bool RunLeastSquaresStage(const RunConfig& config, const StageConfig& stage,
                          const ModelHandle& model, const std::vector<ParameterSpec>& specs,
                          TrajectoryCache* cache, StageResult* result, std::string* error) {
  const auto start_time = std::chrono::steady_clock::now();
  const ModelInfo& info = model.info();
  std::vector<RegressionRecord> records;
  if (!PrepareRegressionRecords(config, stage.experiments, model, stage.regression_data, cache,
                                &records, error)) {
    return false;
  }
  LeastSquaresResult ls;
  LeastSquaresSummary summary;
  if (!RunLeastSquares(model, specs, stage.least_squares, &records, &ls, &summary)) {
    *error = summary.message;
    return false;
  }
  StageResult r;
  r.name = stage.options.name;
  r.model = info.name;
  const bool lasso = stage.least_squares.regression.penalty == Penalty::kLasso;
  if (stage.least_squares.bootstrap.runs > 0) {
    const auto bootstrap_start = std::chrono::steady_clock::now();
    std::string message;
    if (!BootstrapLeastSquares(model, specs, stage.least_squares, records, ls, summary,
                               &r.bootstrap, &message)) {
      r.bootstrap = BootstrapSummary();
      r.bootstrap.message = message;
    }
    r.bootstrap.time_seconds = std::chrono::duration<double>(
        std::chrono::steady_clock::now() - bootstrap_start).count();
  }
  // The lasso's regressions have no covariance: its standard errors are the bootstrap's, as
  // are those of parameters without an analytic one (searched inside the regressors).
  auto standard_error = [&](const std::string& name, double analytic) {
    if (!lasso && std::isfinite(analytic)) return analytic;
    const int k = r.bootstrap.Find(name);
    return k < 0 ? std::numeric_limits<double>::quiet_NaN() : r.bootstrap.std_error[k];
  };
  for (size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].role == ParameterRole::kPerExperiment) {  // named as output error names them
      for (const ExperimentValue& v : ls.per_experiment) {
        if (v.parameter != static_cast<int>(i)) continue;
        Estimate e = ParameterEstimate(
            specs[i], v.value,
            standard_error(specs[i].name + "[" + v.experiment + "]", v.std_error));
        e.name = specs[i].name + "[" + v.experiment + "]";
        e.experiment = v.experiment;
        const auto carried = specs[i].experiment_starts.find(v.experiment);
        if (carried != specs[i].experiment_starts.end()) e.start = carried->second;
        e.undetermined = v.undetermined;
        r.estimates.push_back(e);
      }
      continue;
    }
    Estimate e = ParameterEstimate(specs[i], ls.values[i],
                                   standard_error(specs[i].name, ls.std_errors[i]));
    e.undetermined = ls.undetermined[i];
    r.estimates.push_back(e);
  }
  // Correlations of the regressed parameters (those with a covariance).
  const int n = static_cast<int>(ls.covariance.rows());
  if (n > 0 && ls.covariance.allFinite() && !lasso) {
    const Eigen::VectorXd sd = ls.covariance.diagonal().cwiseSqrt();
    r.correlation = ls.covariance.array() / (sd * sd.transpose()).array();
    for (int k = 0; k < n; ++k) r.correlation_names.push_back(info.parameters[ls.free[k]]);
  }
  StageSummary& s = r.summary;
  s.name = stage.options.name;
  s.usable = true;
  LocalSolveSummary solve;
  solve.run = solve.usable = true;
  solve.iterations = summary.profile_evaluations;
  solve.termination = "least_squares";
  solve.time_seconds = summary.time_seconds;
  double cost = 0.0;
  ExperimentFit fit;
  fit.experiment = "equation-error";
  char line[256];
  for (const EquationSummary& e : summary.equations) {
    cost += 0.5 * e.residual_rms * e.residual_rms * e.samples;
    fit.channels.push_back(
        RegressionMetrics("equation-error", e.state + "'", e.samples, e.residual_rms, e.r2));
    std::snprintf(line, sizeof(line),
                  "equation %s': %d samples, %d rejected, lambda %.3g, R2 %.5f, rms %.4g",
                  e.state.c_str(), e.samples, e.rejected, e.lambda, e.r2, e.residual_rms);
    s.notes.push_back(line);
  }
  solve.initial_cost = solve.final_cost = cost;
  s.refinements.push_back(solve);
  s.chosen = 0;
  s.fits.push_back(fit);
  s.notes.insert(s.notes.end(), summary.notes.begin(), summary.notes.end());
  if (r.bootstrap.done()) s.notes.push_back(BootstrapDescription(r.bootstrap));
  s.uncertainty.message = lasso ? "none: lasso regressions have no covariance"
                                 : "from the regression covariances (minimum distance)";
  if (r.bootstrap.done()) {
    s.uncertainty.message = std::string(lasso ? "" : "analytic (from the regression "
                                                     "covariances); also ") +
                            BootstrapDescription(r.bootstrap);
  }
  s.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  *result = std::move(r);
  return true;
}

}  // namespace vesselid

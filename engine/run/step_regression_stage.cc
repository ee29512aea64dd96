#include "engine/run/step_regression_stage.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "engine/base/elapsed.h"
#include "engine/step_regression/step_regression_bootstrap.h"

namespace vesselid {

bool RunStepRegressionStage(const RunConfig& config, const StageConfig& stage,
                            const ModelHandle& model, const std::vector<ParameterSpec>& specs,
                            TrajectoryCache* cache, StageResult* result, std::string* error) {
  const auto start_time = SteadyClock::now();
  const ModelInfo& info = model.info();
  const DampingInertiaForm* form = model.damping_inertia_form();
  if (form == nullptr) {
    *error = "model " + info.name + " has no damping-inertia form";
    return false;
  }
  std::vector<RegressionRecord> records;
  if (!PrepareRegressionRecords(config, stage.experiments, model, stage.regression_data, cache,
                                &records, error)) {
    return false;
  }
  auto report = std::make_shared<StepRegressionReport>();
  if (!RunStepRegression(*form, records, stage.step_regression, report.get(), error)) {
    return false;
  }
  std::vector<double> values;
  for (const ParameterSpec& spec : specs) values.push_back(spec.start);
  StoreStepRegression(*form, *report, &values);
  std::vector<bool> estimated(info.parameters.size(), false);
  for (int i = 0; i < 2; ++i) {
    for (int k : form->damping[i]) estimated[k] = true;
    for (int k : form->inertia[i]) estimated[k] = true;
    estimated[form->asymptote_a[i]] = estimated[form->asymptote_b[i]] = true;
  }

  StageResult r;
  r.name = stage.options.name;
  r.model = info.name;
  if (stage.step_regression.bootstrap.runs > 0) {
    const auto bootstrap_start = SteadyClock::now();
    std::string message;
    if (!BootstrapStepRegression(*form, *report, stage.step_regression, info.parameters,
                                 &r.bootstrap, &message)) {
      r.bootstrap = BootstrapSummary();
      r.bootstrap.message = message;
    }
    r.bootstrap.time_seconds = SecondsSince(bootstrap_start);
  }
  // The form's parameters are estimated without bounds; their standard errors are the
  // bootstrap's (the lasso has no covariance), NaN without one.
  for (size_t i = 0; i < specs.size(); ++i) {
    ParameterSpec spec = specs[i];
    double std_error = std::numeric_limits<double>::quiet_NaN();
    if (estimated[i]) {
      spec.role = ParameterRole::kFree;
      spec.lower = -std::numeric_limits<double>::infinity();
      spec.upper = std::numeric_limits<double>::infinity();
      const int k = r.bootstrap.Find(spec.name);
      if (k >= 0) std_error = r.bootstrap.std_error[k];
    }
    r.estimates.push_back(ParameterEstimate(spec, values[i], std_error));
  }
  StageSummary& s = r.summary;
  s.name = stage.options.name;
  s.usable = true;
  LocalSolveSummary solve;
  solve.run = solve.usable = true;
  solve.termination = "step_regression";
  ExperimentFit fit;
  fit.experiment = "step-regression";
  double cost = 0.0;
  char line[256];
  const StepSamples& samples = report->samples;
  s.notes.insert(s.notes.end(), samples.notes.begin(), samples.notes.end());
  std::snprintf(line, sizeof(line), "samples: %zu damping, %zu + %zu inertia (mirrored included)",
                samples.damping.size(), samples.inertia[0].size(), samples.inertia[1].size());
  s.notes.push_back(line);
  for (const TermRegression& t : report->terms) {
    cost += 0.5 * t.rms * t.rms * t.samples;
    fit.channels.push_back(RegressionMetrics("step-regression", t.name, t.samples, t.rms, t.r2));
    const int nonzero = t.path.nonzero[t.path.best];
    if (t.asymptote_grid.empty()) {
      std::snprintf(line, sizeof(line),
                    "%s: %d samples in %d groups, lambda %.3g (LOO-CV %.4g), %d nonzero, R2 %.4f",
                    t.name.c_str(), t.samples, t.groups, t.lambda,
                    t.path.cv_error[t.path.best], nonzero, t.r2);
    } else {
      std::snprintf(line, sizeof(line),
                    "%s: %d samples in %d groups, a %.3g, b %.3g, lambda %.3g (LOO-CV %.4g), "
                    "%d nonzero, R2 %.4f",
                    t.name.c_str(), t.samples, t.groups, t.a, t.b, t.lambda,
                    t.path.cv_error[t.path.best], nonzero, t.r2);
    }
    s.notes.push_back(line);
  }
  if (r.bootstrap.done()) s.notes.push_back(BootstrapDescription(r.bootstrap));
  solve.initial_cost = solve.final_cost = cost;
  solve.time_seconds = report->normalisation_seconds + report->regression_seconds +
                       samples.window_seconds + samples.fit_seconds;
  s.refinements.push_back(solve);
  s.chosen = 0;
  s.fits.push_back(fit);
  s.uncertainty.message = r.bootstrap.done() ? BootstrapDescription(r.bootstrap)
                                             : "none: lasso estimates have no covariance";
  r.step_regression = std::move(report);
  s.time_seconds = SecondsSince(start_time);
  *result = std::move(r);
  return true;
}

}  // namespace vesselid

#include "engine/run/held_out.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include "engine/base/parallel_for.h"
#include "engine/model/experiment_window.h"
#include "engine/run/fit_residuals.h"
#include "engine/solve/covariance.h"

namespace vesselid {
namespace {

// A held-out run's own unknowns (its initial states, its per-experiment parameters) are
// solved to a relative cost change (and step) of 1e-8 and a gradient of 1e-10 at the
// tightest: the fit they give is a measure, reported to four digits, and a stage's own
// tolerances (1e-12 by default, for its parameters) would only add iterations here (a fifth
// of an input-gain campaign's run). A fit that crawls (ten iterations together lowering the
// cost by less than 1e-4 of it) is stopped there: at a stage's start values a 120 s spiral's
// initial states spent 190 iterations taking the last 0.3 % off its cost (now 43 iterations;
// that start's held-out MAE moved by up to 6 %, against an estimate's thousands of times lower).
constexpr double kHeldOutSolveTolerance = 1e-8;
constexpr double kHeldOutGradientTolerance = 1e-10;
constexpr int kHeldOutStallWindow = 10;
constexpr double kHeldOutStallTolerance = 1e-4;

}  // namespace

std::unique_ptr<OutputErrorProblem> HeldOutProblem(
    const ModelHandle& model, std::vector<Experiment> experiments,
    const std::vector<std::string>& free_states, const LocalSolveOptions& local,
    const std::vector<double>& values, std::string* error,
    const std::vector<ParameterSpec>& per_experiment, const InitialStatePrior& prior) {
  std::vector<ParameterSpec> fixed;
  for (size_t i = 0; i < values.size(); ++i) {
    ParameterSpec spec;
    spec.name = model.info().parameters[i];
    spec.start = values[i];
    spec.role = ParameterRole::kFixed;
    for (const ParameterSpec& own : per_experiment) {
      if (own.name == spec.name) spec = own;
    }
    fixed.push_back(spec);
  }
  OutputErrorOptions problem_options;
  problem_options.free_initial_states = free_states;
  problem_options.prior = prior;
  auto problem =
      OutputErrorProblem::Create(&model, std::move(experiments), fixed, problem_options, error);
  if (problem == nullptr) return nullptr;
  if (problem->num_free() > 0) {
    LocalSolveOptions own = local;
    own.initial_radius = kNearOptimumRadius;  // from the measured states
    own.function_tolerance = std::max(own.function_tolerance, kHeldOutSolveTolerance);
    own.parameter_tolerance = std::max(own.parameter_tolerance, kHeldOutSolveTolerance);
    own.gradient_tolerance = std::max(own.gradient_tolerance, kHeldOutGradientTolerance);
    own.stall_window = kHeldOutStallWindow;
    own.stall_tolerance = kHeldOutStallTolerance;
    LocalSolveSummary summary;
    if (!RunLocalSolve(own, problem.get(), &summary)) {
      *error = (per_experiment.empty() ? "initial-state estimate: "
                                       : "estimate of the per-experiment parameters: ") +
               summary.message;
      return nullptr;
    }
  }
  return problem;
}

HeldOutPerRun PerRunFromStage(const StageResult& stage, const ModelInfo& model,
                              HeldOutPerExperiment mode) {
  HeldOutPerRun per_run;
  per_run.mode = mode;
  std::vector<int> runs;
  for (const Estimate& e : stage.estimates) {
    if (e.kind != EstimateKind::kParameter || e.role != ParameterRole::kPerExperiment ||
        e.experiment.empty()) {
      continue;
    }
    const std::string name = e.name.substr(0, e.name.find('['));
    if (model.ParameterIndex(name) < 0) continue;
    size_t k = 0;
    while (k < per_run.parameters.size() && per_run.parameters[k].name != name) ++k;
    if (k == per_run.parameters.size()) {
      ParameterSpec spec;
      spec.name = name;
      spec.role = ParameterRole::kPerExperiment;
      spec.start = e.start;
      spec.lower = e.lower;
      spec.upper = e.upper;
      per_run.parameters.push_back(spec);
      per_run.fit_start.push_back(0.0);
      per_run.spread.push_back(0.0);
      runs.push_back(0);
    }
    per_run.fit_start[k] += e.value;
    per_run.spread[k] += e.value * e.value;
    ++runs[k];
  }
  // Held (without, and per_experiment: hold) and started from at the training runs' mean,
  // never one training run's value.
  for (size_t k = 0; k < runs.size(); ++k) {
    ParameterSpec& spec = per_run.parameters[k];
    const double mean = per_run.fit_start[k] / runs[k];
    per_run.spread[k] =
        runs[k] < 2 ? std::nan("")
                    : std::sqrt(std::max(0.0, (per_run.spread[k] - runs[k] * mean * mean) /
                                                  (runs[k] - 1)));
    per_run.fit_start[k] = std::clamp(mean, spec.lower, spec.upper);
    spec.start = per_run.fit_start[k];
  }
  return per_run;
}

namespace {

// The run's per-experiment estimates (value, standard error) from its solved problem; the
// start reported is the value held without them.
void CollectEstimates(OutputErrorProblem* problem, const HeldOutPerRun& per_run,
                      std::vector<Estimate>* estimates) {
  double cost = 0.0;
  Uncertainty u;
  const bool known = problem->Cost(&cost) && ComputeUncertainty(problem, cost, &u);
  const std::vector<Variable>& variables = problem->variables();
  for (size_t i = 0; i < variables.size(); ++i) {
    const Variable& v = variables[i];
    if (v.kind != Variable::Kind::kParameter || v.role != ParameterRole::kPerExperiment) continue;
    Estimate e;
    e.name = v.name;
    e.role = ParameterRole::kPerExperiment;
    e.experiment = problem->experiments()[v.experiment].name;
    e.value = v.value();
    e.std_error = known ? u.StdError(static_cast<int>(i)) : std::nan("");
    for (const ParameterSpec& spec : per_run.parameters) {
      if (spec.name == problem->model().info().parameters[v.index]) e.start = spec.start;
    }
    e.lower = v.lower;
    e.upper = v.upper;
    for (int index : u.undetermined_variables) e.undetermined |= index == static_cast<int>(i);
    estimates->push_back(e);
  }
}

// The standard errors of a burn-in's estimates assume white residuals; a short burn-in of a
// model that is not the ship's leaves them coloured (lag-1 autocorrelation rho near 1), and
// its estimates are worth fewer samples: n (1 - rho) / (1 + rho) (an AR(1) residual's
// effective count). Each standard error is scaled by sqrt((1 + rho) / (1 - rho)), rho the
// largest lag-1 autocorrelation of the burn-in's outputs.
void InflateForColouredResiduals(const ModelInfo& info, const OutputErrorProblem& problem,
                                 std::vector<Estimate>* estimates) {
  std::vector<ExperimentFit> fits;
  std::string why;
  if (!EvaluateFit(problem, &fits, &why)) return;
  double rho = 0.0;
  for (const ResidualAnalysis& a : AnalyseFitResiduals(info, problem.experiments(), fits)) {
    if (std::isfinite(a.lag1)) rho = std::max(rho, a.lag1);
  }
  rho = std::min(rho, 0.999);
  const double factor = std::sqrt((1.0 + rho) / (1.0 - rho));
  for (Estimate& e : *estimates) e.std_error *= factor;
}

// Each of the run's own estimates combined with the training runs' values (HeldOutPerRun);
// `values` (model order) take the combined values, `weighed` the parameters combined (those
// with a training spread). True if any value changed.
bool CombineWithTrainingRuns(const ModelInfo& info, const HeldOutPerRun& per_run,
                             std::vector<Estimate>* estimates, std::vector<double>* values,
                             std::vector<std::string>* weighed) {
  bool changed = false;
  for (Estimate& e : *estimates) {
    for (size_t k = 0; k < per_run.parameters.size(); ++k) {
      const std::string& name = per_run.parameters[k].name;
      if (e.name != name && e.name.rfind(name + "[", 0) != 0) continue;
      const double s = per_run.spread[k], m = per_run.fit_start[k];
      if (!(s > 0.0)) continue;  // one training run, or all alike: the estimate stands
      if (std::find(weighed->begin(), weighed->end(), name) == weighed->end())
        weighed->push_back(name);
      const double se = e.std_error;
      double value = m, sigma = s;
      if (std::isfinite(se) && se > 0.0 && !e.undetermined) {
        const double precision = 1.0 / (se * se) + 1.0 / (s * s);
        value = (e.value / (se * se) + m / (s * s)) / precision;
        sigma = 1.0 / std::sqrt(precision);
      }
      changed |= value != e.value;
      e.value = std::clamp(value, e.lower, e.upper);
      e.std_error = sigma;
      (*values)[info.ParameterIndex(name)] = e.value;
    }
  }
  return changed;
}

// The index of the output that measures state s in `experiment`, or -1.
int MeasuringOutput(const ModelInfo& info, const Experiment& experiment, size_t s) {
  const int o = info.OutputIndex(info.states[s]);
  return o >= 0 && experiment.output_sample_count[o] > 0 ? o : -1;
}

// The burn-in of `experiment` in s: `burn_in` if given, else kBurnInShare of the run; at least
// kMinBurnInIntervals sample intervals and at most half the run either way (the report says
// where a given one was changed).
double BurnInOf(const Experiment& experiment, double burn_in) {
  const double t0 = experiment.node_time.front();
  const double duration = experiment.node_time.back() - t0;
  const double interval = duration / std::max(1, experiment.num_nodes() - 1);
  double b = burn_in > 0.0 ? burn_in : kBurnInShare * duration;
  b = std::min(std::max(b, kMinBurnInIntervals * interval), 0.5 * duration);
  return LastNodeUntil(experiment, t0 + b) - t0;
}

// A held-out run's problem as HeldOutProblem solves it, with its per-experiment parameters
// (if any) starting from `per_run`'s fit start.
std::unique_ptr<OutputErrorProblem> RunProblem(const ModelHandle& model, Experiment experiment,
                                               const std::vector<std::string>& free_states,
                                               const LocalSolveOptions& local,
                                               const std::vector<double>& values,
                                               const HeldOutPerRun* per_run,
                                               const InitialStatePrior& prior, std::string* why) {
  std::vector<ParameterSpec> own;
  if (per_run != nullptr) {
    own = per_run->parameters;
    for (size_t k = 0; k < own.size(); ++k) own[k].start = per_run->fit_start[k];
  }
  std::vector<Experiment> one;
  one.push_back(std::move(experiment));
  return HeldOutProblem(model, std::move(one), free_states, local, values, why, own, prior);
}

// The run predicted from its measured start (HeldOutStart::kMeasured): measured states at
// their measurement; the listed unmeasured states (from the data's guess) and the run's own
// parameters estimated on the burn-in, then the whole run simulated and scored after it. An
// unmeasured state not listed starts where the stages start it (its given value, else 0).
// `problem` is the burn-in's (null when nothing was estimated, or on failure); with
// `residuals`, the analysis of the scored part is appended there.
ExperimentFit PredictFromMeasuredStart(const ModelHandle& model, const Experiment& measured,
                                       const std::vector<std::string>& free_states,
                                       const LocalSolveOptions& local,
                                       const std::vector<double>& values,
                                       const HeldOutPerRun* per_run, const HeldOutStart& start,
                                       std::unique_ptr<OutputErrorProblem>* problem,
                                       std::vector<Estimate>* estimates,
                                       std::vector<ResidualAnalysis>* residuals) {
  const ModelInfo& info = model.info();
  ExperimentFit fit;
  fit.experiment = measured.name;
  fit.start.mode = HeldOutStartModeToString(HeldOutStart::Mode::kMeasured);
  fit.start.requested_burn_in = start.burn_in;
  auto failed = [&fit](const std::string& why) {
    fit.diverged = true;
    fit.message = why;
    return fit;
  };
  std::vector<std::string> unmeasured;
  for (size_t s = 0; s < info.states.size(); ++s) {
    if (MeasuringOutput(info, measured, s) >= 0) continue;
    if (std::find(free_states.begin(), free_states.end(), info.states[s]) != free_states.end())
      unmeasured.push_back(info.states[s]);
  }
  const bool own = per_run != nullptr && !per_run->parameters.empty();
  std::vector<double> at = values;
  std::vector<double> x0 = measured.initial_state;
  double scored_from = -std::numeric_limits<double>::infinity();
  std::string why;
  if (!unmeasured.empty() || own) {
    fit.start.burn_in = BurnInOf(measured, start.burn_in);
    scored_from = measured.node_time.front() + fit.start.burn_in;
    const Experiment burn_in = ExperimentUntil(measured, scored_from);
    *problem = RunProblem(model, burn_in, unmeasured, local, values, own ? per_run : nullptr,
                          start.prior, &why);
    if (*problem == nullptr) return failed("burn-in: " + why);
    fit.start.estimated = unmeasured;
    at = (*problem)->ParametersOf(0);
    if (own) {
      for (const ParameterSpec& spec : per_run->parameters) fit.start.estimated.push_back(spec.name);
      std::vector<Estimate> own_estimates;
      CollectEstimates(problem->get(), *per_run, &own_estimates);
      InflateForColouredResiduals(info, **problem, &own_estimates);
      if (CombineWithTrainingRuns(info, *per_run, &own_estimates, &at, &fit.start.weighed) &&
          !unmeasured.empty()) {
        // The unmeasured states again, with the run's own parameters at the combined values.
        *problem = RunProblem(model, burn_in, unmeasured, local, at, nullptr, start.prior, &why);
        if (*problem == nullptr) return failed("burn-in: " + why);
      }
      if (estimates != nullptr) *estimates = std::move(own_estimates);
    }
    const std::vector<double> estimated = (*problem)->InitialStateOf(0);
    for (const std::string& state : unmeasured) {
      const int s = info.StateIndex(state);
      x0[s] = estimated[s];
    }
  }
  fit.start.initial_state = x0;
  fit.start.values = at;
  std::vector<Experiment> one{measured};
  one.front().initial_state = std::move(x0);
  const std::unique_ptr<OutputErrorProblem> whole =
      HeldOutProblem(model, std::move(one), {}, local, at, &why);
  if (whole == nullptr) return failed(why);
  std::vector<ExperimentFit> evaluated;
  EvaluateFit(*whole, &evaluated, &why, scored_from);  // a divergence is recorded in the fit
  HeldOutStartReport report = std::move(fit.start);
  fit = std::move(evaluated.front());
  fit.start = std::move(report);
  if (residuals != nullptr && !fit.diverged) {
    for (ResidualAnalysis& a : AnalyseFitResiduals(info, whole->experiments(), {fit}))
      residuals->push_back(std::move(a));
  }
  return fit;
}

// Each measured state the refitted start of `problem` (one run) estimated, against its
// measurement in `experiment`.
std::vector<StartOffset> RefittedOffsets(const ModelInfo& info, const Experiment& experiment,
                                         const OutputErrorProblem& problem,
                                         const std::vector<std::string>& free_states) {
  std::vector<StartOffset> offsets;
  const std::vector<double> x0 = problem.InitialStateOf(0);
  for (size_t s = 0; s < info.states.size(); ++s) {
    const int o = MeasuringOutput(info, experiment, s);
    if (o < 0 || std::find(free_states.begin(), free_states.end(), info.states[s]) ==
                     free_states.end()) {
      continue;
    }
    StartOffset offset;
    offset.state = info.states[s];
    offset.measured = experiment.initial_state[s];
    offset.refitted = x0[s];
    offset.noise = experiment.NoiseLevel(o);
    // An unwrapped angle a whole turn off is a turn off; a wrapped one is compared modulo one.
    double d = offset.refitted - offset.measured;
    if (experiment.Wrapped(o)) d = std::remainder(d, 2.0 * M_PI);
    offset.sds = std::isfinite(offset.noise) ? std::abs(d) / offset.noise : std::nan("");
    offsets.push_back(offset);
  }
  return offsets;
}

// One held-out run fitted at `values`, estimating its per-experiment parameters if given, as
// `start` says (HeldOutStart); its residual analysis appended to `residuals` if not null.
ExperimentFit FitOne(const ModelHandle& model, const Experiment& experiment,
                     const std::vector<std::string>& free_states, const LocalSolveOptions& local,
                     const std::vector<double>& values, const HeldOutPerRun* per_run,
                     const HeldOutStart& start, std::vector<Estimate>* estimates,
                     std::vector<ResidualAnalysis>* residuals = nullptr) {
  const bool measured = start.mode == HeldOutStart::Mode::kMeasured;
  std::unique_ptr<OutputErrorProblem> burn_in;
  std::vector<Estimate> measured_estimates;
  ExperimentFit predicted =
      PredictFromMeasuredStart(model, experiment, free_states, local, values, per_run, start,
                               &burn_in, &measured_estimates, measured ? residuals : nullptr);
  if (measured) {
    if (per_run != nullptr && estimates != nullptr) *estimates = std::move(measured_estimates);
    return predicted;
  }
  ExperimentFit fit;
  fit.experiment = experiment.name;
  std::string why;
  const std::unique_ptr<OutputErrorProblem> refit =
      RunProblem(model, experiment, free_states, local, values, per_run, start.prior, &why);
  if (refit == nullptr) {
    fit.diverged = true;
    fit.message = why;
  } else {
    std::vector<ExperimentFit> evaluated;
    EvaluateFit(*refit, &evaluated, &why);  // a divergence is recorded in the fit
    if (residuals != nullptr) {
      for (ResidualAnalysis& a : AnalyseFitResiduals(model.info(), refit->experiments(), evaluated))
        residuals->push_back(std::move(a));
    }
    fit = std::move(evaluated.front());
    fit.start.offsets = RefittedOffsets(model.info(), experiment, *refit, free_states);
    if (per_run != nullptr && estimates != nullptr) CollectEstimates(refit.get(), *per_run, estimates);
  }
  // The refit's report, with the measured start's figures beside it.
  HeldOutStartReport& report = fit.start;
  report.mode = HeldOutStartModeToString(HeldOutStart::Mode::kRefitted);
  report.implausible_sds = start.implausible_sds;
  report.measured_start = std::move(predicted.channels);
  report.measured_start_diverged = predicted.diverged;
  report.burn_in = predicted.start.burn_in;
  report.requested_burn_in = predicted.start.requested_burn_in;
  report.estimated = std::move(predicted.start.estimated);
  report.weighed = std::move(predicted.start.weighed);
  report.refitted = free_states;
  if (per_run != nullptr) {
    for (const ParameterSpec& spec : per_run->parameters) report.refitted.push_back(spec.name);
  }
  return fit;
}

}  // namespace

bool SimulateHeldOutPasses(const RunConfig& config, const ModelHandle& model,
                           const std::vector<std::string>& names, const ExperimentOptions& options,
                           const std::vector<std::string>& free_states,
                           const LocalSolveOptions& local, const std::vector<HeldOutPass>& passes,
                           TrajectoryCache* cache, std::string* error,
                           const HeldOutPerRun& per_run, const HeldOutStart& start) {
  std::vector<Experiment> experiments;
  if (!PrepareExperiments(config, names, model, options, cache, &experiments, error)) {
    return false;
  }
  const bool fit_own = !per_run.parameters.empty() && per_run.mode == HeldOutPerExperiment::kFit;
  // Held values: the per-experiment parameters at their start (PerRunFromStage: the training
  // runs' mean).
  const int count = static_cast<int>(experiments.size());
  const int num_passes = static_cast<int>(passes.size());
  std::vector<std::vector<double>> held(num_passes);
  for (int p = 0; p < num_passes; ++p) {
    held[p] = *passes[p].values;
    for (const ParameterSpec& spec : per_run.parameters) {
      const int index = model.info().ParameterIndex(spec.name);
      if (index >= 0) held[p][index] = spec.start;
    }
  }
  // One problem per run and pass (they share nothing with the shared parameters fixed), so
  // that one that diverges is recorded and the others are still measured. Every run of every
  // pass, and each fit "without" its per-experiment parameters (only where they are
  // reported), is one task of a single parallel batch (local.num_threads; each run's own
  // solve on one thread), each into its own slot, collected in the config's order: the same
  // results on any number of threads.
  struct Task {
    int pass, run;
    bool without;
  };
  std::vector<Task> tasks;
  for (int p = 0; p < num_passes; ++p) {
    for (int e = 0; e < count; ++e) {
      tasks.push_back({p, e, false});
      if (fit_own && passes[p].parameters != nullptr) tasks.push_back({p, e, true});
    }
  }
  std::vector<ExperimentFit> with(num_passes * count), without(num_passes * count);
  std::vector<std::vector<Estimate>> estimates(num_passes * count);
  std::vector<std::vector<ResidualAnalysis>> analyses(num_passes * count);
  LocalSolveOptions one_run = local;
  one_run.initial_radius = kNearOptimumRadius;
  if (tasks.size() > 1) one_run.num_threads = 1;
  ParallelFor(static_cast<int>(tasks.size()), local.num_threads, [&](int t) {
    const Task& task = tasks[t];
    const int slot = task.pass * count + task.run;
    const Experiment& experiment = experiments[task.run];
    if (task.without) {
      without[slot] = FitOne(model, experiment, free_states, one_run, held[task.pass], nullptr,
                             start, nullptr);
      without[slot].trace = Trajectory();
      return;
    }
    std::vector<ResidualAnalysis>* own =
        passes[task.pass].residuals != nullptr ? &analyses[slot] : nullptr;
    if (!fit_own) {
      with[slot] =
          FitOne(model, experiment, free_states, one_run, held[task.pass], nullptr, start, nullptr,
                 own);
    } else {
      with[slot] = FitOne(model, experiment, free_states, one_run, *passes[task.pass].values,
                          &per_run, start, &estimates[slot], own);
    }
  });
  for (int p = 0; p < num_passes; ++p) {
    const HeldOutPass& pass = passes[p];
    if (pass.parameters != nullptr) {
      *pass.parameters = HeldOutParameters();
      for (const ParameterSpec& spec : per_run.parameters)
        pass.parameters->parameters.push_back(spec.name);
      pass.parameters->fitted = fit_own;
    }
    pass.fits->clear();
    if (pass.residuals != nullptr) pass.residuals->clear();
    for (int e = 0; e < count; ++e) {
      const int slot = p * count + e;
      pass.fits->push_back(std::move(with[slot]));
      if (pass.residuals != nullptr) {
        for (ResidualAnalysis& a : analyses[slot]) pass.residuals->push_back(std::move(a));
      }
      if (fit_own && pass.parameters != nullptr) {
        pass.parameters->without.push_back(std::move(without[slot]));
        for (Estimate& est : estimates[slot]) pass.parameters->estimates.push_back(std::move(est));
      }
    }
  }
  return true;
}

bool SimulateHeldOut(const RunConfig& config, const ModelHandle& model,
                     const std::vector<std::string>& names, const ExperimentOptions& options,
                     const std::vector<std::string>& free_states, const LocalSolveOptions& local,
                     const std::vector<double>& values, TrajectoryCache* cache,
                     std::vector<ExperimentFit>* fits, std::string* error,
                     const HeldOutPerRun& per_run, HeldOutParameters* parameters,
                     std::vector<ResidualAnalysis>* residuals, const HeldOutStart& start) {
  return SimulateHeldOutPasses(config, model, names, options, free_states, local,
                               {{&values, fits, parameters, residuals}}, cache, error, per_run,
                               start);
}

std::vector<std::string> HeldOutBoundNotes(const HeldOutParameters& parameters) {
  std::vector<std::string> notes;
  for (const Estimate& e : parameters.estimates) {
    const int side = BoundSide(e.value, e.lower, e.upper);
    if (side == 0) continue;
    const bool at_lower = side < 0;
    char text[256];
    std::snprintf(text, sizeof(text),
                  "validation: %s of held-out run '%s' is at its %s bound %g: the run's data "
                  "pull it further",
                  e.name.c_str(), e.experiment.c_str(), at_lower ? "lower" : "upper",
                  at_lower ? e.lower : e.upper);
    notes.push_back(text);
  }
  return notes;
}

namespace {

// Per output: MAE pooled over the runs named in `common` (those neither set of values made
// diverge); the number of runs that diverged.
void Pool(const std::vector<ExperimentFit>& fits, const std::set<std::string>& common,
          std::map<std::string, double>* mae, int* diverged) {
  std::map<std::string, std::pair<double, int>> sums;
  *diverged = 0;
  for (const ExperimentFit& fit : fits) {
    if (fit.diverged) {
      ++*diverged;
      continue;
    }
    if (common.count(fit.experiment) == 0) continue;
    for (const ChannelMetrics& c : fit.channels) {
      sums[c.output].first += c.mae * c.samples;
      sums[c.output].second += c.samples;
    }
  }
  for (const auto& [output, sum] : sums) {
    if (sum.second > 0) (*mae)[output] = sum.first / sum.second;
  }
}

}  // namespace

double MeanMaeRatio(const HeldOutCheck& check) {
  double sum = 0.0;
  int count = 0;
  for (size_t i = 0; i < check.outputs.size(); ++i) {
    if (check.start_mae[i] > 0.0) sum += check.stage_mae[i] / check.start_mae[i], ++count;
  }
  return count > 0 ? sum / count : std::nan("");
}

HeldOutCheck CompareHeldOut(const std::vector<ExperimentFit>& start,
                            const std::vector<ExperimentFit>& stage) {
  HeldOutCheck check;
  check.done = true;
  // The MAE compares like with like: the runs both sets of values simulate to the end.
  std::set<std::string> start_ok, common;
  for (const ExperimentFit& fit : start) {
    if (!fit.diverged) start_ok.insert(fit.experiment);
  }
  for (const ExperimentFit& fit : stage) {
    if (!fit.diverged && start_ok.count(fit.experiment) > 0) common.insert(fit.experiment);
  }
  std::map<std::string, double> start_mae, stage_mae;
  Pool(start, common, &start_mae, &check.start_diverged);
  Pool(stage, common, &stage_mae, &check.stage_diverged);
  for (const auto& [output, mae] : stage_mae) {
    auto before = start_mae.find(output);
    if (before == start_mae.end()) continue;
    check.outputs.push_back(output);
    check.start_mae.push_back(before->second);
    check.stage_mae.push_back(mae);
  }
  const double mean = MeanMaeRatio(check);
  const double ratio = std::isnan(mean) ? 1.0 : mean;
  // More diverging runs make a stage worse unless its start is far worse on the runs both
  // simulate: a guard never falls back to values that are worse still (the start of a
  // least-squares stage is the config's guess, not a model).
  check.start_far_worse = ratio < kStartFarWorse && !std::isnan(mean);
  check.worse = (check.stage_diverged > check.start_diverged && !check.start_far_worse) ||
                (check.stage_diverged == check.start_diverged && ratio > kHeldOutTolerance);
  return check;
}

bool PredictsBetter(const std::vector<ExperimentFit>& a, const std::vector<ExperimentFit>& b) {
  const HeldOutCheck check = CompareHeldOut(b, a);  // a as the "stage" against b
  if (check.stage_diverged > check.start_diverged) return false;
  if (check.stage_diverged < check.start_diverged) return true;
  return MeanMaeRatio(check) < 1.0;  // false for NaN
}

std::string DescribeHeldOut(const HeldOutCheck& check, const DisplayUnitOf& unit_of,
                            const std::string& experiment) {
  std::string text;
  if (check.stage_diverged > check.start_diverged) {
    text = std::to_string(check.stage_diverged) + " held-out run(s) diverge (" +
           std::to_string(check.start_diverged) + " at " + check.BaselineText() + ")";
  }
  for (size_t i = 0; i < check.outputs.size(); ++i) {
    const DisplayUnit unit =
        unit_of ? unit_of(experiment, check.outputs[i]) : DisplayUnit{"", 1.0};
    char item[160];
    std::snprintf(item, sizeof(item), "%s %.4g -> %.4g%s", check.outputs[i].c_str(),
                  unit.scale * check.start_mae[i], unit.scale * check.stage_mae[i],
                  unit.unit.empty() ? "" : (" " + unit.unit).c_str());
    text += (text.empty() ? "held-out MAE "
             : i == 0     ? "; held-out MAE "
                          : ", ") +
            std::string(item);
  }
  return text;
}

std::string DescribeReferenceCheck(const RunResult& run, const DisplayUnitOf& unit_of) {
  const HeldOutCheck& check = run.reference_check;
  std::string text = DescribeHeldOut(
      check, unit_of, run.final_validation.empty() ? "" : run.final_validation[0].experiment);
  const std::string of = " of " + std::to_string(run.final_validation.size()) + " run(s)";
  if (check.start_diverged > 0) {
    text += (text.empty() ? "" : "; ") + std::string("the reference diverged on ") +
            std::to_string(check.start_diverged) + of;
  }
  if (check.stage_diverged > 0 && check.stage_diverged <= check.start_diverged) {
    text += "; the final values diverged on " + std::to_string(check.stage_diverged) + of;
  }
  if (check.outputs.empty()) text += "; no run both simulate to compare";
  return text;
}

}  // namespace vesselid

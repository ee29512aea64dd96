#include "engine/run/output_error_stage.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>

#include "engine/base/format_numbers.h"
#include "engine/base/nan.h"
#include "engine/base/statistics.h"
#include "engine/model/channel_weights.h"
#include "engine/run/bootstrap_uncertainty.h"
#include "engine/run/continuation.h"
#include "engine/run/estimate_specs.h"
#include "engine/run/disturbance_choice.h"
#include "engine/run/free_run_drift.h"
#include "engine/run/omitted_term_test.h"
#include "engine/run/disturbance_notes.h"
#include "engine/run/fit_residuals.h"
#include "engine/run/innovation_structure.h"
#include "engine/run/input_noise_notes.h"
#include "engine/run/input_noise_uncertainty.h"
#include "engine/run/records.h"
#include "engine/run/stage_weights.h"
#include "engine/solve/noise_weights.h"
#include "engine/solve/step_stability.h"

namespace vesselid {
namespace {

// The stage's result from its solved problem; `starts` are the reported start values by
// variable name (a variable without one, e.g. the noise parameters of the disturbance model
// `noise: auto` chose, reports none: its solve started from the candidates' own starts).
StageResult Collect(const OutputErrorProblem& problem, const std::map<std::string, double>& starts,
                    StageSummary summary) {
  StageResult result;
  result.name = summary.name;
  result.model = problem.model().info().name;
  const std::vector<Variable>& variables = problem.variables();
  const Uncertainty& u = summary.uncertainty;
  for (size_t i = 0; i < variables.size(); ++i) {
    const Variable& v = variables[i];
    if (v.kind == Variable::Kind::kInputCorrection) continue;  // summarised in the notes
    Estimate e;
    e.name = v.name;
    e.kind = v.kind == Variable::Kind::kParameter ? EstimateKind::kParameter
             : v.kind == Variable::Kind::kNoise   ? EstimateKind::kNoise
                                                  : EstimateKind::kInitialState;
    e.role = v.role;
    e.experiment = v.experiment >= 0 ? problem.experiments()[v.experiment].name : "";
    e.value = v.value();
    const auto start = starts.find(v.name);
    e.start = start != starts.end() ? start->second : kUnknown;
    e.std_error = v.free ? u.StdError(static_cast<int>(i)) : kUnknown;
    e.lower = v.lower;
    e.upper = v.upper;
    for (int index : u.undetermined_variables) e.undetermined |= index == static_cast<int>(i);
    result.estimates.push_back(e);
  }
  if (u.available) {
    std::vector<int> kept;  // matrix rows of the reported variables (no input corrections)
    for (size_t k = 0; k < u.variables.size(); ++k) {
      const Variable& v = variables[u.variables[k]];
      if (v.kind == Variable::Kind::kInputCorrection) continue;
      kept.push_back(static_cast<int>(k));
      result.correlation_names.push_back(v.name);
    }
    result.correlation.resize(kept.size(), kept.size());
    for (size_t a = 0; a < kept.size(); ++a) {
      for (size_t b = 0; b < kept.size(); ++b)
        result.correlation(a, b) = u.correlation(kept[a], kept[b]);
    }
  }
  InputNoiseNotes(problem, &summary.notes, &summary.findings);
  result.summary = std::move(summary);
  return result;
}

constexpr int kMaxStepReductions = 2;

// While the estimate's dynamics are faster than the integration step can follow
// (step_stability.h), prepares the experiments with a step that can and refines again from
// the estimate; the step used goes to result->integration_step (0: the configured one).
bool FollowTheDynamics(const RunConfig& config, const StageConfig& stage, const ModelHandle& model,
                       const StageOptions& options, const NoiseModel& noise, TrajectoryCache* cache,
                       std::unique_ptr<OutputErrorProblem>* problem, StageSummary* summary,
                       StageResult* result, std::string* error) {
  ExperimentOptions finer = stage.experiment;
  for (int reduction = 0;; ++reduction) {
    const StepStability stability = CheckStepStability(**problem);
    if (stability.worst <= kStepStabilityLimit) return true;
    bool failed = false;
    for (const ExperimentFit& fit : summary->fits) {
      for (const ChannelMetrics& m : fit.channels) failed |= FitFailed(m);
    }
    if (failed) {  // a shorter step would refine a fit that missed the data anyway
      Finding f = MakeFinding(FindingKind::kIntegrationStep,
                              "integration step too long for the estimate's dynamics (" +
                                  stability.Describe() +
                                  "), and the fit failed: not refined again at a shorter step");
      f.value = stability.worst;
      f.threshold = kStepStabilityLimit;
      summary->findings.push_back(std::move(f));
      return true;
    }
    if (reduction == kMaxStepReductions) {
      Finding f = MakeFinding(FindingKind::kIntegrationStep,
                              "integration step too long for the estimate's dynamics after " +
                                  std::to_string(kMaxStepReductions) +
                                  " reductions: " + stability.Describe() +
                                  "; the estimate may fit the integrator, not the vessel");
      f.value = stability.worst;
      f.threshold = kStepStabilityLimit;
      summary->findings.push_back(std::move(f));
      return true;
    }
    finer.max_step = stability.SafeStep();
    char text[128];
    std::snprintf(
        text, sizeof(text),
        "integration step reduced to %.3g s and the stage refined again: ", finer.max_step);
    // Handled: the stage is solved again at a step that follows the dynamics.
    Finding reduced = MakeFinding(FindingKind::kIntegrationStep, text + stability.Describe());
    reduced.severity = FindingSeverity::kInfo;
    reduced.value = finer.max_step;
    summary->findings.push_back(std::move(reduced));
    std::vector<Experiment> experiments;
    if (!PrepareExperiments(config, stage.experiments, model, finer, cache, &experiments, error)) {
      return false;
    }
    if (noise.active()) {  // the stage's noise weights, not the configured ones
      for (Experiment& e : experiments) SetChannelWeights(noise.Weights(model.info()), &e);
    }
    std::unique_ptr<OutputErrorProblem> refined = RefineFromEstimate(
        **problem, std::move(experiments), stage.problem, options, summary, error);
    if (refined == nullptr) {
      *error = "refinement with the integration step reduced to " + std::to_string(finer.max_step) +
               " s: " + *error;
      return false;
    }
    *problem = std::move(refined);
    result->integration_step = finer.max_step;
  }
}

// Names the experiments the fit does not serve (OutlierOptions) and, if asked, refines again
// with them down-weighted or dropped.
bool HandleOutliers(const StageConfig& stage, const StageOptions& options,
                    std::unique_ptr<OutputErrorProblem>* problem, StageSummary* summary,
                    std::string* error) {
  const OutputErrorProblem& solved = **problem;
  const int count = static_cast<int>(solved.experiments().size());
  if (count < 3 || static_cast<int>(summary->fits.size()) != count) return true;
  std::vector<double> rms;
  for (const ExperimentFit& fit : summary->fits) rms.push_back(fit.rms_cost);
  const double limit = OutlierLimit(rms, stage.outliers.threshold);
  std::vector<double> factor(count, 1.0);  // weight scale per experiment
  std::vector<std::pair<double, std::string>> costly, far;
  for (int e = 0; e < count; ++e) {
    if (rms[e] > limit) {
      costly.emplace_back(rms[e], solved.experiments()[e].name);
      factor[e] = std::min(factor[e], limit / rms[e]);
    }
  }
  int free_states = 0;
  for (const Variable& v : solved.variables()) {
    if (v.kind != Variable::Kind::kInitialState || !v.free) continue;
    ++free_states;
    const Experiment& e = solved.experiments()[v.experiment];
    const double sigma = v.index < static_cast<int>(e.initial_state_sigma.size())
                             ? e.initial_state_sigma[v.index]
                             : std::nan("");
    const double guess = e.initial_state_guess[v.index];
    const double z = std::abs(v.value() - guess) / sigma;
    if (!(z > 3.0)) continue;
    far.emplace_back(z, v.name + FormatNumbers(" = %.4g (guess %.4g +- %.2g, %.0f standard errors)",
                                        v.value(), guess, sigma, z));
    factor[v.experiment] = std::min(factor[v.experiment], 3.0 / z);
  }
  auto list = [](std::vector<std::pair<double, std::string>> items) {
    std::sort(items.rbegin(), items.rend());
    std::string text;
    for (size_t i = 0; i < items.size() && i < 6; ++i)
      text += (i > 0 ? ", " : "") + items[i].second;
    return text + (items.size() > 6 ? ", ..." : "");
  };
  if (!costly.empty()) {
    for (auto& [cost, name] : costly) name += FormatNumbers(" (%.3g)", cost);
    Finding f = MakeFinding(
        FindingKind::kOutliers,
        std::to_string(costly.size()) + " of " + std::to_string(count) +
            " experiments fit far worse than the rest (RMS cost above " + FormatNumbers("%.3g", limit) +
            " = max(median + " + FormatNumbers("%g", stage.outliers.threshold) + " x MAD, " +
            FormatNumbers("%g", 1.0 + stage.outliers.threshold / kOutlierFloorScale) +
            " x median)): " + list(costly));
    f.count = static_cast<int>(costly.size());
    f.threshold = limit;
    summary->findings.push_back(std::move(f));
  }
  if (!far.empty()) {
    Finding f = MakeFinding(FindingKind::kOutliers,
                            std::to_string(far.size()) + " of " + std::to_string(free_states) +
                                " initial states end far from the data's guess: " + list(far));
    f.count = static_cast<int>(far.size());
    f.threshold = 3.0;
    // The guess is the data's own (a derivative of smooth model-test records is sharply
    // "known"), so a state far from it is no doubt about the fit: context.
    f.severity = FindingSeverity::kInfo;
    summary->findings.push_back(std::move(f));
  }
  if (stage.outliers.action == OutlierOptions::Action::kNote || (costly.empty() && far.empty())) {
    return true;
  }
  std::vector<Experiment> experiments;
  int acted = 0;
  for (int e = 0; e < count; ++e) {
    Experiment experiment = solved.experiments()[e];
    if (factor[e] < 1.0) {
      ++acted;
      if (stage.outliers.action == OutlierOptions::Action::kDrop) continue;
      for (ExperimentSample& sample : experiment.samples) sample.weight *= factor[e];
      experiment.prior_weight *= factor[e];
    }
    experiments.push_back(std::move(experiment));
  }
  const bool drop = stage.outliers.action == OutlierOptions::Action::kDrop;
  summary->notes.push_back("outliers: the stage refined again with " + std::to_string(acted) +
                           " experiment(s) " + (drop ? "dropped" : "down-weighted"));
  std::unique_ptr<OutputErrorProblem> refined =
      RefineFromEstimate(solved, std::move(experiments), stage.problem, options, summary, error);
  if (refined == nullptr) {
    *error = "refinement without the outliers: " + *error;
    return false;
  }
  *problem = std::move(refined);
  return true;
}

// The multistart's search horizons (search_horizons.h) become the stage's continuation
// when it has none of its own; `on_pieces` says whether they did.
bool SetSearchHorizons(const RunConfig& config, const ModelHandle& model, TrajectoryCache* cache,
                       StageConfig* stage, bool* on_pieces, std::string* error) {
  *on_pieces = false;
  const SearchHorizons& horizons = stage->search_horizons;
  if (!stage->options.use_global_start || stage->options.global.algorithm != "multistart" ||
      !stage->continuation.empty() || horizons.mode == SearchHorizons::Mode::kNone) {
    return true;
  }
  std::vector<Experiment> experiments;
  if (!PrepareExperiments(config, stage->experiments, model, stage->experiment, cache,
                          &experiments, error)) {
    return false;
  }
  stage->continuation =
      horizons.mode == SearchHorizons::Mode::kAuto ? AutomaticHorizons(experiments) : horizons.lengths;
  *on_pieces = !stage->continuation.empty();
  // A piece begins mid-record, where the data give the measured states but only a guess of
  // the others (velocities from differenced positions): those are estimated per piece. A
  // state the model never moves (an inactive degree of freedom) keeps a zero Jacobian column,
  // which the damped steps leave alone.
  const ModelInfo& info = model.info();
  for (size_t i = 0; i < info.states.size(); ++i) {
    const int output = info.OutputIndex(info.states[i]);
    bool measured = false;
    for (const Experiment& e : experiments) {
      measured = measured || (output >= 0 && e.output_sample_count[output] > 0);
    }
    if (!measured) stage->continuation_free_states.push_back(info.states[i]);
  }
  return true;
}

// After a search on pieces: the first phase's global start, its notes and findings, are the
// stage's, and a note says which start the whole experiments' refinement kept (refinement 0
// and 1 from the search's end point, the last from the configured start).
void CarrySearch(StageSummary searched, double horizon, StageSummary* summary) {
  summary->global = std::move(searched.global);
  summary->global.horizon_seconds = horizon;
  char text[256];
  std::snprintf(text, sizeof(text), "global start on %.3g s pieces", horizon);
  const std::string prefix = "global start";
  for (const std::string& note : searched.notes) {
    if (note.rfind(prefix, 0) != 0) continue;
    summary->notes.push_back(text + note.substr(prefix.size()));
  }
  summary->findings.insert(summary->findings.end(), searched.findings.begin(),
                           searched.findings.end());
  const int from_start = static_cast<int>(summary->refinements.size()) - 1;
  const LocalSolveSummary& start = summary->refinements[from_start];
  char start_cost[64] = "failed";
  if (start.usable) std::snprintf(start_cost, sizeof(start_cost), "%.6e", start.final_cost);
  std::snprintf(text, sizeof(text),
                "global start, whole experiments: the %s kept, cost %.6e (refined from the "
                "configured start: %s)",
                summary->chosen == from_start ? "refinement from the configured start"
                                              : "refinement of the search's end point",
                summary->local().final_cost, start_cost);
  summary->notes.push_back(text);
}

}  // namespace

bool RunOutputErrorStage(const RunConfig& config, const StageConfig& configured_stage,
                         const ModelHandle& model, std::vector<ParameterSpec>* resolved,
                         TrajectoryCache* cache, const ProgressCallback& progress,
                         StageResult* result, std::string* error) {
  // The stage with its experiments prepared as its weighting needs (stage_weights.h).
  StageConfig stage = configured_stage;
  const bool noise_weights = UsesNoiseWeights(config, stage);
  stage.experiment = StageExperimentOptions(config, stage);
  std::vector<ParameterSpec>& specs = *resolved;
  const std::vector<ParameterSpec> configured = specs;
  std::vector<StateAt> states;
  std::vector<std::string> continuation_notes;
  const auto stage_start = std::chrono::steady_clock::now();
  bool on_pieces = false;
  StageSummary searched;
  if (!SetSearchHorizons(config, model, cache, &stage, &on_pieces, error) ||
      !RunContinuation(config, stage, model, cache, progress, &specs, &states, &continuation_notes,
                       on_pieces ? &searched : nullptr, error)) {
    return false;
  }
  std::vector<Experiment> experiments;
  if (!PrepareExperiments(config, stage.experiments, model, stage.experiment, cache, &experiments,
                          error)) {
    return false;
  }
  std::unique_ptr<OutputErrorProblem> problem =
      OutputErrorProblem::Create(&model, std::move(experiments), specs, stage.problem, error);
  if (problem == nullptr) return false;
  // After continuation the stage is refined twice: from the initial states the short
  // segments estimated, and from the data's guess (the latter sometimes finds the lower
  // of two nearby minima; both cost one refinement).
  std::vector<std::vector<double>> extra_starts;
  // The configured start (the data's initial states): reported as the start, and after a
  // search on pieces refined too, so that the search is never worse than a local solve.
  std::vector<double> starts = problem->Values();
  for (size_t i = 0; i < starts.size(); ++i) {
    const Variable& v = problem->variables()[i];
    if (v.kind == Variable::Kind::kParameter && v.experiment < 0) {
      starts[i] = configured[v.index].start;
    }
  }
  std::map<std::string, double> start_by_name;
  for (size_t i = 0; i < starts.size(); ++i) start_by_name[problem->variables()[i].name] = starts[i];
  if (!states.empty()) {
    extra_starts.push_back(problem->Values());
    SetCarriedStates(states, problem.get());
  }
  if (on_pieces) extra_starts.push_back(starts);
  StageOptions options = stage.options;
  options.use_global_start = options.use_global_start && stage.continuation.empty();
  if (stage.problem.disturbance.method == DisturbanceSpec::Method::kFilterError) {
    options.uncertainty = FilterErrorUncertainty(options.uncertainty);
  }
  options.local.progress = progress;
  options.global.progress = progress;
  SetFirstSolveWeights(config, stage, problem.get());
  // The weights the first solve uses, by experiment, for the comparable cost.
  std::map<std::string, std::vector<double>> first_weights;
  {
    const std::vector<std::vector<double>> w = problem->ChannelWeights();
    for (size_t e = 0; e < w.size(); ++e) first_weights[problem->experiments()[e].name] = w[e];
  }
  StageSummary summary;
  if (!RunStage(options, problem.get(), &summary, extra_starts)) {
    *error = summary.message;
    return false;
  }
  if (problem->filter_error()) {
    NameFilterErrorUncertainty(stage.options.uncertainty, &summary.uncertainty);
  }
  if (on_pieces) CarrySearch(std::move(searched), stage.continuation.front(), &summary);
  NoiseModel noise;
  if (noise_weights && !IterateNoiseWeights(options, problem.get(), &summary, &noise)) {
    *error = summary.message;
    return false;
  }
  if (!FollowTheDynamics(config, stage, model, options, noise, cache, &problem, &summary, result,
                         error) ||
      !HandleOutliers(stage, options, &problem, &summary, error)) {
    return false;
  }
  std::vector<DisturbanceCandidate> candidates;
  if (stage.problem.disturbance.method == DisturbanceSpec::Method::kAuto) {
    if (!ChooseDisturbance(stage, options,
                           AnalyseFitResiduals(model.info(), problem->experiments(), summary.fits),
                           &problem, &summary, &candidates, error)) {
      return false;
    }
  }
  if (options.compute_uncertainty && IsBootstrap(options.uncertainty.method)) {
    // On the final problem: after the noise weights, step reductions and outlier refinement.
    BootstrapStageUncertainty(options, stage.problem, problem.get(), &summary);
  }
  // The filter-error method carries the inputs' noise as process noise, in its likelihood.
  if (!problem->filter_error()) {
    AddInputNoiseSpread(config, cache, options, stage.problem, problem.get(), &summary);
  }
  summary.notes.insert(summary.notes.begin(), continuation_notes.begin(), continuation_notes.end());
  // The cost at the end point with the first solve's weights: under noise weights the
  // minimised cost is ~N/2 wherever the solve ends, this one ranks end points.
  double comparable_cost = summary.local().final_cost;
  if (noise.active()) {
    std::vector<std::vector<double>> weights = problem->ChannelWeights();
    for (size_t e = 0; e < weights.size(); ++e) {
      const auto found = first_weights.find(problem->experiments()[e].name);
      if (found != first_weights.end()) weights[e] = found->second;
    }
    if (!problem->CostWithChannelWeights(weights, &comparable_cost)) comparable_cost = kUnknown;
  }
  const double integration_step = result->integration_step;
  // Under the filter-error method the verdict reads the filter's innovations: a correct ship
  // and disturbance leave them white whatever colour the free run's residuals have.
  std::vector<ResidualAnalysis> residuals =
      problem->filter_error()
          ? AnalyseInnovations(*problem)
          : AnalyseFitResiduals(model.info(), problem->experiments(), summary.fits);
  DisturbanceNotes(summary.name, *problem, summary.uncertainty, residuals, &summary.notes,
                   &summary.findings);
  AddInnovationStructureFindings(summary.name, TestInnovationStructure(*problem), &summary.notes,
                                 &summary.findings);
  std::vector<double> operating_range = problem->OperatingRange();
  const std::vector<OmittedTermTest> omitted = TestOmittedTerms(*problem, operating_range);
  AddOmittedTermFindings(summary.name, omitted, &summary.notes, &summary.findings);
  for (ResidualAnalysis& a : residuals) {
    const auto& share = summary.uncertainty.input_noise_share;
    const auto e = share.find(a.experiment);
    if (e == share.end()) continue;
    const auto o = e->second.find(a.output);
    if (o != e->second.end()) a.input_noise_share = o->second;
  }
  // The stage's time includes the analysis of its residuals, as it does its uncertainty.
  // Only where a free run is called failed or poor: the drift note stands beside those.
  bool missed = false;
  for (const ExperimentFit& fit : summary.fits) {
    for (const ChannelMetrics& m : fit.channels) missed = missed || FitFailed(m) || FitPoor(m);
  }
  std::vector<FreeRunDrift> drift;
  if (missed && AllScored(omitted)) drift = MeasureFreeRunDrift(*problem);
  summary.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stage_start).count();
  *result = Collect(*problem, start_by_name, std::move(summary));
  result->free_run_drift = std::move(drift);
  result->disturbance = ReportDisturbance(stage.problem.disturbance, *problem,
                                          result->summary.uncertainty, candidates);
  result->integration_step = integration_step;
  result->residuals = std::move(residuals);
  result->noise_model = std::move(noise);
  result->comparable_cost = comparable_cost;
  result->state_limits = std::move(operating_range);
  return true;
}

}  // namespace vesselid

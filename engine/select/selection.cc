#include "engine/select/selection.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>

#include "engine/base/json_number.h"
#include "engine/base/statistics.h"
#include "engine/output/identified_model.h"
#include "engine/run/filter_prediction.h"
#include "engine/run/display_units.h"
#include "engine/run/pipeline.h"
#include "engine/select/selection_choice.h"
#include "engine/study/study_runner.h"

namespace vesselid {
namespace {

using nlohmann::json;

bool Contains(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

// The outputs run `experiment` maps in every candidate.
std::vector<std::string> CommonOutputs(const std::vector<NamedCandidate>& candidates,
                                       const std::string& experiment) {
  std::vector<std::string> common;
  for (size_t c = 0; c < candidates.size(); ++c) {
    const ExperimentSpec* spec = candidates[c].config.FindExperiment(experiment);
    std::vector<std::string> mapped;
    if (spec != nullptr) {
      for (const auto& [output, column] : spec->outputs) mapped.push_back(output);
    }
    if (c == 0) {
      common = mapped;
    } else {
      common.erase(std::remove_if(common.begin(), common.end(),
                                  [&](const std::string& o) { return !Contains(mapped, o); }),
                   common.end());
    }
  }
  return common;
}

// The candidate's config for one fold: every stage fitted without the held-out runs, those
// predicted by the final validation; `held_out` empty: every run fitted, no validation.
bool FoldConfig(const RunConfig& base, const std::vector<std::string>& held_out, RunConfig* out,
                std::string* error) {
  RunConfig config = base;
  std::vector<std::string> free_states = config.final_validation.free_initial_states;
  for (StageConfig& stage : config.stages) {
    stage.experiments.erase(
        std::remove_if(stage.experiments.begin(), stage.experiments.end(),
                       [&](const std::string& e) { return Contains(held_out, e); }),
        stage.experiments.end());
    if (stage.experiments.empty()) {
      *error = "stage '" + stage.options.name + "' has no runs left when the fold holds out " +
               JoinNames(held_out);
      return false;
    }
    stage.validation.clear();
    if (!config.has_final_validation) free_states = stage.problem.free_initial_states;
  }
  config.has_final_validation = !held_out.empty();
  config.final_validation.experiments = held_out;
  config.final_validation.free_initial_states = free_states;
  config.final_validation.per_experiment = HeldOutPerExperiment::kFit;
  config.velocity_validation = false;
  *out = std::move(config);
  return true;
}

// A filter-error candidate's held-out runs predicted through its filter with the final values
// (filter_prediction.h): per run and scored output, the one-step and k-step fits.
json FilterPredictions(const RunConfig& config, const RunResult& result,
                       const std::vector<std::string>& held_out,
                       const std::vector<std::string>& outputs, TrajectoryCache* records) {
  json rows = json::array();
  const StageResult& last = result.stages.back();
  if (!DisturbanceFromEstimates(last.estimates).active()) return rows;
  IdentifiedModel model;
  std::string error;
  if (!IdentifiedModelOf(config, result, 0, 0, &model, &error)) return rows;
  StageConfig stage = config.stages.back();
  stage.validation = held_out;
  StageResult scored = last;
  scored.validation = result.final_validation;  // the free runs beside
  scored.disturbance.predictions.clear();
  PredictHeldOutThroughFilter(config, stage, *model.handle, model.values, records, &scored);
  for (const FilterPrediction& p : scored.disturbance.predictions) {
    if (!Contains(outputs, p.output)) continue;
    rows.push_back({{"run", p.experiment},
                    {"output", p.output},
                    {"steps", p.steps},
                    {"k_step_fit_percent", JsonNumber(p.k_step_fit_percent)},
                    {"one_step_fit_percent", JsonNumber(p.one_step_fit_percent)}});
  }
  return rows;
}

// The likelihood of the last stage's fit on every run (selection_result.h): the filter's, or
// the Gaussian one of output error's residuals with their variances estimated.
void AddLikelihood(const StageResult& last, json* j) {
  int noise = 0, samples = 0;
  double nll = 0.0;
  for (const Estimate& e : last.estimates) {
    if (e.kind == EstimateKind::kNoise && e.role != ParameterRole::kFixed) ++noise;
  }
  for (const ExperimentFit& fit : last.summary.fits) {
    for (const ChannelMetrics& m : fit.channels) samples += m.samples;
  }
  if (noise > 0 && std::isfinite(last.disturbance.negative_log_likelihood)) {
    nll = last.disturbance.negative_log_likelihood;
    (*j)["disturbance"] = last.disturbance.model;
  } else {
    // Pooled per output over the runs: n_o/2 (ln(2 pi RSS_o/n_o) + 1).
    std::map<std::string, std::pair<double, int>> per_output;
    for (const ExperimentFit& fit : last.summary.fits) {
      for (const ChannelMetrics& m : fit.channels) {
        per_output[m.output].first += m.rmse * m.rmse * m.samples;
        per_output[m.output].second += m.samples;
      }
    }
    for (const auto& [output, sums] : per_output) {
      const auto [rss, n] = sums;
      if (n == 0 || !(rss > 0.0)) return;
      nll += 0.5 * n * (std::log(2.0 * M_PI * rss / n) + 1.0);
    }
    noise = static_cast<int>(per_output.size());
  }
  (*j)["negative_log_likelihood"] = nll;
  (*j)["noise_unknowns"] = noise;
  (*j)["likelihood_samples"] = samples;
}

json RunCase(const NamedCandidate& candidate, const std::vector<std::string>& held_out,
             const std::vector<std::string>& outputs) {
  RunConfig config;
  std::string error;
  if (!FoldConfig(candidate.config, held_out, &config, &error)) {
    return {{"usable", false}, {"message", error}};
  }
  RunResult result;
  TrajectoryCache records;
  if (!RunIdentification(config, &result, &error, {}, {}, &records) ||
      !result.stopped_stage.empty()) {
    return {{"usable", false}, {"message", error.empty() ? result.stop_message : error}};
  }
  json j = {{"usable", true}, {"model", config.model->info().name}};
  auto channels = [&](const std::vector<ExperimentFit>& fits, bool scale_rss) {
    json rows = json::array();
    for (const ExperimentFit& fit : fits) {
      if (fit.diverged) {
        rows.push_back({{"run", fit.experiment}, {"diverged", true}, {"message", fit.message}});
        continue;
      }
      json row = {{"run", fit.experiment}, {"diverged", false}};
      for (const ChannelMetrics& m : fit.channels) {
        if (!Contains(outputs, m.output)) continue;
        const DisplayUnit unit = OutputDisplayUnit(config, fit.experiment, m.output);
        const double rmse = m.rmse * unit.scale;
        row["outputs"][m.output] = {{"fit_percent", m.fit_percent},
                                    {"rmse", rmse},
                                    {"unit", unit.unit},
                                    {"samples", m.samples}};
        if (scale_rss) row["outputs"][m.output]["rss"] = rmse * rmse * m.samples;
      }
      rows.push_back(row);
    }
    return rows;
  };
  if (!held_out.empty()) {
    j["runs"] = channels(result.final_validation, false);
    j["filter"] = FilterPredictions(config, result, held_out, outputs, &records);
    return j;
  }
  // The fit on every run: the last output-error stage's fits; what was estimated.
  const StageResult& last = result.stages.back();
  j["runs"] = channels(last.summary.fits, true);
  int shared = 0, per_run = 0;
  for (const FinalParameter& p : result.parameters) {
    if (p.role == ParameterRole::kPerExperiment) {
      per_run += p.runs;
    } else if (p.role != ParameterRole::kFixed) {
      ++shared;
    }
  }
  const StageConfig& last_config = config.stages.back();
  j["shared_parameters"] = shared;
  j["per_run_values"] = per_run;
  j["initial_states"] = static_cast<int>(last_config.problem.free_initial_states.size() *
                                         last_config.experiments.size());
  AddLikelihood(last, &j);
  return j;
}

}  // namespace

std::vector<std::vector<std::string>> FoldsByRun(const std::vector<std::string>& runs, int folds) {
  const int k =
      folds <= 0 ? static_cast<int>(runs.size()) : std::min(folds, static_cast<int>(runs.size()));
  std::vector<std::vector<std::string>> out(k);
  for (size_t i = 0; i < runs.size(); ++i) out[i % k].push_back(runs[i]);
  return out;
}

bool RunSelection(const std::vector<NamedCandidate>& candidates, const SelectionOptions& options,
                  SelectionResult* result, std::string* error,
                  const std::function<void(const std::string&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  if (candidates.size() < 2) {
    *error = "select: needs at least two candidates";
    return false;
  }
  if (options.runs.size() < 2) {
    *error = "select: needs at least two runs to cross-validate over";
    return false;
  }
  if (options.folds == 1) {
    *error = "select: folds must be >= 2 (or leave_one_run_out)";
    return false;
  }
  std::vector<std::string> outputs = options.outputs;
  for (const std::string& run : options.runs) {
    for (const NamedCandidate& c : candidates) {
      if (c.config.FindExperiment(run) == nullptr) {
        *error = "select: candidate '" + c.name + "' has no experiment '" + run + "'";
        return false;
      }
    }
    const std::vector<std::string> common = CommonOutputs(candidates, run);
    if (options.outputs.empty()) {
      if (outputs.empty() && run == options.runs.front()) outputs = common;
      outputs.erase(std::remove_if(outputs.begin(), outputs.end(),
                                   [&](const std::string& o) { return !Contains(common, o); }),
                    outputs.end());
    } else {
      for (const std::string& o : options.outputs) {
        if (!Contains(common, o)) {
          *error =
              "select: output '" + o + "' is not mapped by every candidate in run '" + run + "'";
          return false;
        }
      }
    }
  }
  if (outputs.empty()) {
    *error = "select: the candidates map no output in common to score";
    return false;
  }
  SelectionResult out;
  out.folds = FoldsByRun(options.runs, options.folds);
  const int folds = static_cast<int>(out.folds.size());
  out.method = options.folds <= 0 ? "leave-one-run-out" : std::to_string(folds) + "-fold by run";
  out.outputs = outputs;
  const int per_candidate = folds + 1;  // the folds, then the fit on every run
  const int count = static_cast<int>(candidates.size()) * per_candidate;
  std::vector<json> cases;
  RunCases(
      count,
      [&](int index) {
        const NamedCandidate& c = candidates[index / per_candidate];
        const int fold = index % per_candidate;
        return RunCase(c, fold < folds ? out.folds[fold] : std::vector<std::string>{}, outputs);
      },
      options.cases, &cases,
      [&](int index, const json& r) {
        if (!progress) return;
        const int fold = index % per_candidate;
        progress("select: " + candidates[index / per_candidate].name + ", " +
                 (fold < folds ? "fold " + std::to_string(fold + 1) : std::string("all runs")) +
                 (r.value("usable", false) ? "" : ": " + r.value("message", std::string())));
      });
  if (cases.empty()) return true;  // not rank 0
  for (size_t c = 0; c < candidates.size(); ++c) {
    SelectionCandidate s;
    s.name = candidates[c].name;
    s.model = candidates[c].config.model->info().name;
    s.usable = true;
    std::vector<std::vector<double>> fit(outputs.size()), rmse(outputs.size());
    std::vector<double> k_step, one_step;  // per fold, through the filter
    for (int f = 0; f < folds; ++f) {
      const json& r = cases[c * per_candidate + f];
      if (r.contains("filter") && !r["filter"].empty()) {
        double k_sum = 0.0, one_sum = 0.0;
        for (const json& p : r["filter"]) {
          k_sum += NumberOr(p["k_step_fit_percent"], NAN);
          one_sum += NumberOr(p["one_step_fit_percent"], NAN);
          s.prediction_steps = p["steps"].get<int>();
        }
        k_step.push_back(k_sum / r["filter"].size());
        one_step.push_back(one_sum / r["filter"].size());
      }
      if (!r.value("usable", false)) {
        s.usable = false;
        s.message = "fold " + std::to_string(f + 1) + ": " + r.value("message", std::string());
        break;
      }
      std::vector<double> fold_fit(outputs.size(), 0.0), fold_rmse(outputs.size(), 0.0);
      double sum = 0.0;
      int terms = 0;
      for (const json& run : r["runs"]) {
        if (run["diverged"].get<bool>()) {
          s.usable = false;
          s.message = "run '" + run["run"].get<std::string>() +
                      "' held out: " + run.value("message", std::string("diverged"));
          break;
        }
        for (size_t o = 0; o < outputs.size(); ++o) {
          const json& m = run["outputs"][outputs[o]];
          fold_fit[o] += m["fit_percent"].get<double>() / r["runs"].size();
          fold_rmse[o] += m["rmse"].get<double>() / r["runs"].size();
          sum += m["fit_percent"].get<double>();
          ++terms;
          if (s.outputs.size() < outputs.size()) {
            s.outputs.push_back({outputs[o], m["unit"].get<std::string>()});
          }
        }
      }
      if (!s.usable) break;
      s.fold_scores.push_back(sum / terms);
      for (size_t o = 0; o < outputs.size(); ++o) {
        fit[o].push_back(fold_fit[o]);
        rmse[o].push_back(fold_rmse[o]);
      }
    }
    const json& all = cases[c * per_candidate + folds];
    if (s.usable && !all.value("usable", false)) {
      s.usable = false;
      s.message = "fit on every run: " + all.value("message", std::string());
    }
    if (s.usable) {
      const MeanSd scores = Summarise(s.fold_scores);
      s.score = scores.mean;
      s.score_se = scores.sd / std::sqrt(static_cast<double>(folds));
      for (size_t o = 0; o < outputs.size(); ++o) {
        const MeanSd f = Summarise(fit[o]);
        s.outputs[o].fit_percent = f.mean;
        s.outputs[o].fit_sd = f.sd;
        s.outputs[o].rmse = Summarise(rmse[o]).mean;
      }
      s.shared_parameters = all["shared_parameters"].get<int>();
      s.per_run_values = all["per_run_values"].get<int>();
      s.initial_states = all["initial_states"].get<int>();
      s.complexity = s.shared_parameters;
      double rss = 0.0;
      for (const json& run : all["runs"]) {
        if (run["diverged"].get<bool>()) continue;
        for (const std::string& o : outputs) {
          rss += run["outputs"][o]["rss"].get<double>();
          s.samples += run["outputs"][o]["samples"].get<int>();
        }
      }
      const double n = s.samples, k = s.shared_parameters + s.per_run_values + s.initial_states;
      s.rss = rss;
      if (n > 0 && rss > 0) {
        s.aic = n * std::log(rss / n) + 2 * k;
        s.bic = n * std::log(rss / n) + k * std::log(n);
      }
      if (all.contains("negative_log_likelihood")) {
        s.disturbance = all.value("disturbance", std::string());
        s.negative_log_likelihood = all["negative_log_likelihood"].get<double>();
        s.likelihood_samples = all["likelihood_samples"].get<int>();
        s.likelihood_unknowns = static_cast<int>(k) + all["noise_unknowns"].get<int>();
        if (s.likelihood_samples > 0) {
          s.likelihood_bic = 2.0 * s.negative_log_likelihood +
                             s.likelihood_unknowns * std::log(s.likelihood_samples);
        }
      }
      // Through the filter: where every fold has its predictions.
      if (static_cast<int>(k_step.size()) == folds) {
        s.k_step_fit_percent = Summarise(k_step).mean;
        s.one_step_fit_percent = Summarise(one_step).mean;
      }
    }
    out.candidates.push_back(std::move(s));
  }
  out.likelihoods_comparable = true;
  int samples = -1;
  bool held_starts = false, filtered = false;
  for (const SelectionCandidate& s : out.candidates) {
    if (!s.usable) continue;
    if (samples >= 0 && s.likelihood_samples != samples) out.likelihoods_comparable = false;
    samples = s.likelihood_samples;
    held_starts = held_starts || (s.disturbance.empty() && s.initial_states == 0);
    filtered = filtered || !s.disturbance.empty();
  }
  if (held_starts && filtered) {
    out.likelihood_note =
        "an output-error candidate holds each run's start at its first samples, a filter-error "
        "candidate takes it as measured with the sensor's noise: the first sample's error then "
        "counts against output error's likelihood for the whole run, and even a tiny process "
        "noise that lets the filter correct it scores better; free the starts "
        "(free_initial_states) to compare the disturbance models alone";
  }
  ChooseByOneStandardError(&out);
  out.time_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  *result = std::move(out);
  return true;
}

}  // namespace vesselid

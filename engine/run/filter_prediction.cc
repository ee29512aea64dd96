#include "engine/run/filter_prediction.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "engine/run/records.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {
namespace {

// 100 (1 - |y - y_hat| / |y - mean y|) over the samples with a finite prediction.
double FitPercent(const std::vector<double>& y, const std::vector<double>& predicted) {
  double mean = 0.0, count = 0.0;
  for (size_t i = 0; i < y.size(); ++i) {
    if (!std::isfinite(predicted[i])) continue;
    mean += y[i];
    count += 1.0;
  }
  if (count < 2.0) return NAN;
  mean /= count;
  double sse = 0.0, sst = 0.0;
  for (size_t i = 0; i < y.size(); ++i) {
    if (!std::isfinite(predicted[i])) continue;
    sse += (y[i] - predicted[i]) * (y[i] - predicted[i]);
    sst += (y[i] - mean) * (y[i] - mean);
  }
  return sst > 0.0 ? 100.0 * (1.0 - std::sqrt(sse / sst)) : NAN;
}

}  // namespace

DisturbanceSpec DisturbanceFromEstimates(const std::vector<Estimate>& estimates) {
  DisturbanceSpec spec;
  std::map<std::string, DisturbanceSpec::Measurement> measurement;
  for (const Estimate& e : estimates) {
    if (e.kind != EstimateKind::kNoise) continue;
    spec.method = DisturbanceSpec::Method::kFilterError;
    const std::string target = e.name.substr(e.name.rfind('.') + 1);
    const std::string head = e.name.substr(0, e.name.rfind('.'));
    if (head == "sigma.white") {
      measurement[target].output = target;
      measurement[target].white_too = true;
    } else if (head == "sigma.ar1" || head == "tau.ar1") {
      measurement[target].output = target;
      measurement[target].type = DisturbanceSpec::Measurement::Type::kAr1;
    } else if (head == "q.process") {
      DisturbanceSpec::Process w;
      w.state = target;
      spec.process.push_back(w);
    } else if (head == "omega.wave") {
      DisturbanceSpec::Wave w;
      w.output = target;
      spec.wave.push_back(w);
    } else if (head == "q.bias") {
      DisturbanceSpec::Bias b;
      b.output = target;
      spec.bias.push_back(b);
    }
  }
  for (auto& [output, m] : measurement) {
    // A white part alone is the default of every compared output; listed, it must keep its type.
    if (m.type == DisturbanceSpec::Measurement::Type::kWhite) m.white_too = false;
    spec.measurement.push_back(m);
  }
  return spec;
}

void PredictHeldOutThroughFilter(const RunConfig& config, const StageConfig& stage,
                                 const ModelHandle& model, const std::vector<double>& values,
                                 TrajectoryCache* cache, StageResult* result) {
  if (stage.validation.empty()) return;
  OutputErrorOptions options;
  options.disturbance = DisturbanceFromEstimates(result->estimates);
  if (!options.disturbance.active()) return;
  options.disturbance.prediction_steps = stage.problem.disturbance.prediction_steps;
  for (const Estimate& e : result->estimates) {
    if (e.kind == EstimateKind::kNoise) options.noise_starts[e.name] = e.value;
  }
  std::vector<Experiment> experiments;
  std::string error;
  if (!PrepareExperiments(config, stage.validation, model, stage.experiment, cache, &experiments,
                          &error)) {
    result->summary.notes.push_back("held-out through the filter: not computed (" + error + ")");
    return;
  }
  std::vector<ParameterSpec> specs;
  const ModelInfo& info = model.info();
  for (size_t i = 0; i < info.parameters.size() && i < values.size(); ++i) {
    ParameterSpec s;
    s.name = info.parameters[i];
    s.start = values[i];
    s.role = ParameterRole::kFixed;
    specs.push_back(s);
  }
  std::unique_ptr<OutputErrorProblem> problem =
      OutputErrorProblem::Create(&model, std::move(experiments), specs, options, &error);
  if (problem == nullptr) {
    result->summary.notes.push_back("held-out through the filter: not computed (" + error + ")");
    return;
  }
  const int k = options.disturbance.prediction_steps;
  std::map<std::pair<std::string, std::string>, double> free_run;
  for (const ExperimentFit& fit : result->validation) {
    for (const ChannelMetrics& m : fit.channels) free_run[{m.experiment, m.output}] = m.fit_percent;
  }
  for (size_t x = 0; x < problem->experiments().size(); ++x) {
    const Experiment& e = problem->experiments()[x];
    FilterRun run;
    if (!problem->RunFilter(static_cast<int>(x), k, &run)) {
      result->summary.notes.push_back("held-out through the filter: " + e.name +
                                      ": the filter diverged");
      continue;
    }
    const double dt = e.num_nodes() > 1 ? (e.node_time.back() - e.node_time.front()) /
                                              (e.num_nodes() - 1)
                                        : 0.0;
    for (size_t j = 0; j < info.outputs.size(); ++j) {
      std::vector<double> y, ahead, one;
      for (int i = 0; i < e.num_samples(); ++i) {
        if (e.samples[i].output != static_cast<int>(j)) continue;
        y.push_back(e.samples[i].value);
        ahead.push_back(run.prediction[i]);
        one.push_back(e.samples[i].value - run.innovation[i]);
      }
      if (y.empty()) continue;
      const auto found = free_run.find({e.name, info.outputs[j]});
      FilterPrediction prediction;
      prediction.experiment = e.name;
      prediction.output = info.outputs[j];
      prediction.steps = k;
      prediction.seconds_ahead = k * dt;
      if (k + 2 <= e.num_nodes()) prediction.k_step_fit_percent = FitPercent(y, ahead);
      prediction.one_step_fit_percent = FitPercent(y, one);
      if (found != free_run.end()) prediction.free_run_fit_percent = found->second;
      result->disturbance.predictions.push_back(prediction);
      char ahead_text[80];
      if (k + 2 <= e.num_nodes()) {
        std::snprintf(ahead_text, sizeof(ahead_text), "%.1f %% (%.3g s ahead)",
                      prediction.k_step_fit_percent, k * dt);
      } else {
        std::snprintf(ahead_text, sizeof(ahead_text), "none (the run has %d nodes)",
                      e.num_nodes());
      }
      char text[320];
      std::snprintf(text, sizeof(text),
                    "held-out through the filter: %s %s: %d-step-ahead fit %s, one-step %.1f %%; "
                    "the stage's validation free run %.1f %%",
                    e.name.c_str(), info.outputs[j].c_str(), k, ahead_text, FitPercent(y, one),
                    found != free_run.end() ? found->second : NAN);
      result->summary.notes.push_back(text);
    }
  }
}

}  // namespace vesselid

#include "engine/study/monte_carlo_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "engine/base/statistics.h"
#include "engine/study/monte_carlo_noise.h"
#include "engine/study/monte_carlo_summary.h"
#include "engine/study/study_stage.h"

namespace vesselid {
namespace {

using nlohmann::json;

constexpr int kMonteCarloPart = 1;  // CaseSeed part of the output noise
constexpr int kInputNoisePart = 5;  // and of the input noise (its own stream: adding input
                                    // noise leaves each run's output noise as it was)

// Truth of every model parameter: the stage's carried values, overridden by `truth`, or by
// the stage's estimate on the data (truth: estimate); every free parameter must be given.
bool ResolveTruth(const StudyStage& stage, const MonteCarloOptions& options,
                  std::vector<double>* truth, std::string* error) {
  truth->clear();
  for (const ParameterSpec& spec : stage.specs) truth->push_back(spec.start);
  const std::vector<std::string>& names = stage.model->info().parameters;
  if (options.truth_estimate) {
    for (int index : stage.free) {
      const auto found = stage.run_optimum.find(names[index]);
      if (found == stage.run_optimum.end()) {
        *error = "the stage's solve gave no estimate of '" + names[index] + "'";
        return false;
      }
      (*truth)[index] = found->second;
    }
    return true;
  }
  for (const auto& [name, value] : options.truth) {
    bool found = false;
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) {
        (*truth)[i] = value;
        found = true;
      }
    }
    if (!found) {
      *error = "truth names '" + name + "', not a parameter of model " + stage.model->info().name;
      return false;
    }
  }
  for (int index : stage.free) {
    if (options.truth.count(names[index]) == 0) {
      *error = "no truth for free parameter '" + names[index] +
               "' (monte_carlo.truth or simulation.truth)";
      return false;
    }
  }
  return true;
}

// The uncertainty method of the runs: one name if they all agree, else each one once.
std::string RunsUncertaintyMethod(std::vector<json>* cases) {
  std::vector<std::string> methods;
  for (json& c : *cases) {
    if (!c.contains("uncertainty_method")) continue;
    const std::string m = c["uncertainty_method"];
    if (std::find(methods.begin(), methods.end(), m) == methods.end()) methods.push_back(m);
    c.erase("uncertainty_method");
  }
  std::string joined;
  for (const std::string& m : methods) joined += (joined.empty() ? "" : ", ") + m;
  return joined.empty() ? "none" : joined;
}

// Under `weights: noise`: per compared output the estimated sigma over the usable runs
// (mean, SD, mean / truth) and the runs whose noise model did not settle; null otherwise.
json NoiseModelSummary(const MonteCarloOptions& options, const std::vector<json>& cases) {
  json outputs = json::array();
  int unsettled = 0, with_model = 0;
  for (const json& c : cases) {
    if (!c.contains("noise_sigma")) continue;
    ++with_model;
    unsettled += c.value("noise_converged", true) ? 0 : 1;
  }
  if (with_model == 0) return nullptr;
  for (const auto& [name, truth] : options.noise) {
    std::vector<double> sigma;
    for (const json& c : cases) {
      if (c.contains("noise_sigma") && c["noise_sigma"].contains(name)) {
        sigma.push_back(NumberOr(c["noise_sigma"][name], NAN));
      }
    }
    if (sigma.empty()) continue;
    const MeanSd m = Summarise(sigma);
    outputs.push_back({{"output", name},
                       {"truth", truth},
                       {"mean", JsonNumber(m.mean)},
                       {"sd", JsonNumber(m.sd)},
                       {"mean_over_truth", JsonNumber(m.mean / truth)},
                       {"runs", m.n}});
  }
  return {{"runs", with_model}, {"unsettled_runs", unsettled}, {"outputs", outputs}};
}

}  // namespace

bool RunMonteCarloStudy(const RunConfig& config, const MonteCarloOptions& options, unsigned seed,
                        const CaseOptions& execution, json* result, std::string* error,
                        const CaseProgress& progress) {
  const auto start_time = std::chrono::steady_clock::now();
  StudyStage stage;
  // A parametric bootstrap first solves the stage on the data, as the run does.
  if (!PrepareStudyStage(config, options.stage, &stage, error, options.truth_estimate)) {
    if (options.truth_estimate) {
      *error =
          options.truth_where + ": estimate: the stage cannot be solved on the data: " + *error;
    }
    return false;
  }
  std::vector<double> truth;
  if (!ResolveTruth(stage, options, &truth, error)) {
    *error = "monte_carlo: " + *error;
    return false;
  }
  std::vector<std::vector<double>> clean;
  if (!SimulateSamples(stage, truth, &clean, error,
                       options.truth_estimate ? &stage.run_optimum : nullptr)) {
    *error = "monte_carlo: truth: " + *error;
    return false;
  }
  MonteCarloNoise noise;
  if (!ResolveMonteCarloNoise(stage, options, options.truth_estimate ? &clean : nullptr, &noise,
                              error)) {
    *error = "monte_carlo: noise: " + *error;
    return false;
  }
  std::vector<ParameterSpec> specs = stage.specs;
  StageOptions stage_options = stage.options;
  if (options.start_at_truth) {
    for (int index : stage.free) specs[index].start = truth[index];
    stage_options.use_global_start = false;  // noise alone, not the search, is measured
  }
  auto run_case = [&](int r) -> json {
    const auto case_start = std::chrono::steady_clock::now();
    std::vector<Experiment> experiments;
    std::string message;
    if (noise.any_input() &&
        !NoisyInputExperiments(stage, noise.input, CaseSeed(seed, kInputNoisePart, r), &experiments,
                               &message)) {
      return {{"run", r}, {"usable", false}, {"message", "input noise: " + message}};
    }
    if (!noise.any_input()) experiments = stage.experiments;
    std::mt19937_64 random(CaseSeed(seed, kMonteCarloPart, r));
    std::normal_distribution<double> normal(0.0, 1.0);
    for (size_t e = 0; e < experiments.size(); ++e) {
      for (size_t i = 0; i < experiments[e].samples.size(); ++i) {
        ExperimentSample& s = experiments[e].samples[i];
        s.value = clean[e][i] + noise.output[s.output] * normal(random);
      }
    }
    StudySolve solve = SolveStudyStage(stage, std::move(experiments), specs, stage_options);
    json c = {{"run", r}, {"usable", solve.usable}};
    if (!solve.usable) {
      c["message"] = solve.message;
    } else {
      json estimates = json::array(), errors = json::array();
      for (double v : solve.Values(stage)) estimates.push_back(JsonNumber(v));
      for (double v : solve.StdErrors(stage)) errors.push_back(JsonNumber(v));
      c["estimates"] = estimates;
      c["std_errors"] = errors;
      if (solve.noise.active()) {
        json sigma = json::object();
        for (size_t k = 0; k < solve.noise.outputs.size(); ++k) {
          sigma[solve.noise.outputs[k]] = JsonNumber(solve.noise.sigma[k]);
        }
        c["noise_sigma"] = sigma;
        c["noise_iterations"] = solve.noise.iterations;
        c["noise_converged"] = solve.noise.converged;
      }
      c["cost"] = solve.summary.local().final_cost;
      c["iterations"] = solve.summary.local().iterations;
      c["uncertainty_method"] = solve.summary.uncertainty.method;
    }
    c["time_seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - case_start).count();
    return c;
  };
  std::vector<json> cases;
  RunCases(options.runs, run_case, execution, &cases, progress);
  if (!ProcessGroup::Current().root()) {
    *result = nullptr;
    return true;
  }
  const double z = TwoSidedZ(options.confidence);
  const ModelInfo& info = stage.model->info();
  json levels = json::object(), of_fit = json::array(), inputs = json::array();
  for (size_t c = 0; c < info.outputs.size(); ++c) {
    if (std::isfinite(noise.output[c])) levels[info.outputs[c]] = noise.output[c];
    if (noise.output_of_fit[c]) of_fit.push_back(info.outputs[c]);
  }
  for (size_t u = 0; u < info.inputs.size(); ++u) {
    if (noise.input[u] > 0.0) {
      levels[info.inputs[u]] = noise.input[u];
      inputs.push_back(info.inputs[u]);
    }
  }
  MonteCarloTruth about;
  about.names = stage.free_names;
  for (int index : stage.free) about.values.push_back(truth[index]);
  if (options.truth_estimate) {
    for (const std::string& name : stage.free_names) {
      const auto se = stage.run_std_errors.find(name);
      about.stage_std_errors.push_back(se != stage.run_std_errors.end() ? se->second : NAN);
    }
  }
  const std::string method = RunsUncertaintyMethod(&cases);
  const json summary = MonteCarloSummary(about, z, cases);
  json notes = json::array();
  if (options.truth_estimate) {
    // An estimate at a bound is a truth the runs cannot scatter around: half of them stop there.
    for (int index : stage.free) {
      const ParameterSpec& spec = stage.specs[index];
      const double value = truth[index];
      const double tolerance = 1e-6 * std::max(1.0, std::abs(value));
      if (std::abs(value - spec.lower) <= tolerance || std::abs(value - spec.upper) <= tolerance) {
        char line[256];
        std::snprintf(line, sizeof(line),
                      "%s: the stage's estimate %.6g is at its bound, so the bootstrap runs "
                      "pile up there: their SD and coverage are not those of an interior "
                      "estimate",
                      spec.name.c_str(), value);
        notes.push_back(line);
      }
    }
  }
  for (const std::string& note :
       MonteCarloNotes(summary, options.confidence, options.truth_estimate, cases)) {
    notes.push_back(note);
  }
  *result = {
      {"stage", stage.stage->options.name},
      {"runs", options.runs},
      {"truth", options.truth_estimate ? "estimate" : "given"},
      {"noise", levels},
      {"noise_from_fit", of_fit},
      {"noisy_inputs", inputs},
      {"start", options.start_at_truth ? "truth" : "stage"},
      {"uncertainty_method", method},
      {"confidence", options.confidence},
      {"z", z},
      {"parameters", stage.free_names},
      {"summary", summary},
      {"notes", notes},
      {"noise_model", NoiseModelSummary(options, cases)},
      {"cases", cases},
      {"time_seconds",
       std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count()}};
  return true;
}

std::string MonteCarloText(const json& result) {
  std::string text;
  char line[512];
  const json& summary = result["summary"];
  const bool bootstrap = result.value("truth", "given") == "estimate";
  std::snprintf(line, sizeof(line),
                "Monte Carlo noise study, stage %s: %d runs (%d usable), start %s, %.0f %% "
                "intervals (z = %.3f, uncertainty method %s), %.1f s\n",
                result["stage"].get<std::string>().c_str(), summary["runs"].get<int>(),
                summary["usable_runs"].get<int>(), result["start"].get<std::string>().c_str(),
                100.0 * result["confidence"].get<double>(), result["z"].get<double>(),
                result.value("uncertainty_method", "").c_str(),
                NumberOr(result["time_seconds"], NAN));
  text += line;
  if (bootstrap) {
    text +=
        "  parametric bootstrap around the stage's estimate on the data (the truth below is "
        "the estimate; bias is the method's bias at the estimate)\n";
  }
  std::string levels;
  for (const auto& [name, sd] : result["noise"].items()) {
    bool fit = false;
    for (const json& f : result.value("noise_from_fit", json::array())) fit |= f == name;
    bool input = false;
    for (const json& f : result.value("noisy_inputs", json::array())) input |= f == name;
    std::snprintf(line, sizeof(line), "%s%s %.4g%s%s", levels.empty() ? "" : ", ", name.c_str(),
                  sd.get<double>(), input ? " (input)" : "", fit ? " (fit residual SD)" : "");
    levels += line;
  }
  text += "  noise SD: " + levels + "\n";
  std::snprintf(line, sizeof(line), "  %-12s %13s %13s %11s %9s %12s %12s %9s %14s%s\n",
                "parameter", bootstrap ? "estimate" : "truth", "mean", "bias %", "bias/SE", "SD",
                "mean SE", "SE/SD", "coverage %", bootstrap ? "      stage SE  SD/stage SE" : "");
  text += line;
  for (const json& p : summary["parameters"]) {
    std::snprintf(
        line, sizeof(line), "  %-12s %13.6g %13.6g %11.4f %9.3f %12.4g %12.4g %9.3f %8.1f +- %.1f",
        p["name"].get<std::string>().c_str(), p["truth"].get<double>(), NumberOr(p["mean"], NAN),
        NumberOr(p["bias_percent"], NAN), NumberOr(p.value("bias_over_std_error", json()), NAN),
        NumberOr(p["sd"], NAN), NumberOr(p["mean_std_error"], NAN),
        NumberOr(p["std_error_over_sd"], NAN), 100.0 * NumberOr(p["coverage"], NAN),
        100.0 * NumberOr(p["coverage_std_error"], NAN));
    text += line;
    if (bootstrap) {
      std::snprintf(line, sizeof(line), " %13.4g %12.3f",
                    NumberOr(p.value("stage_std_error", json()), NAN),
                    NumberOr(p.value("sd_over_stage_std_error", json()), NAN));
      text += line;
    }
    text += "\n";
  }
  for (const json& note : result.value("notes", json::array())) {
    text += "  note: " + note.get<std::string>() + "\n";
  }
  const json& noise = result.contains("noise_model") ? result["noise_model"] : json();
  if (noise.is_object()) {
    std::snprintf(line, sizeof(line),
                  "  noise model (weights: noise), estimated sigma over %d runs (%d did not "
                  "settle):\n  %-12s %13s %13s %12s %12s\n",
                  noise["runs"].get<int>(), noise["unsettled_runs"].get<int>(), "output",
                  "truth", "mean", "SD", "mean/truth");
    text += line;
    for (const json& o : noise["outputs"]) {
      std::snprintf(line, sizeof(line), "  %-12s %13.6g %13.6g %12.4g %12.4f\n",
                    o["output"].get<std::string>().c_str(), o["truth"].get<double>(),
                    NumberOr(o["mean"], NAN), NumberOr(o["sd"], NAN),
                    NumberOr(o["mean_over_truth"], NAN));
      text += line;
    }
  }
  return text;
}

}  // namespace vesselid

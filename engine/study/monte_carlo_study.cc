#include "engine/study/monte_carlo_study.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "engine/base/statistics.h"
#include "engine/study/study_stage.h"

namespace vesselid {
namespace {

using nlohmann::json;

constexpr int kPart = 1;  // CaseSeed part of this study

// Truth of every model parameter: the stage's carried values, overridden by `truth`; every
// free parameter must be given.
bool ResolveTruth(const StudyStage& stage, const MonteCarloOptions& options,
                  std::vector<double>* truth, std::string* error) {
  truth->clear();
  for (const ParameterSpec& spec : stage.specs) truth->push_back(spec.start);
  const std::vector<std::string>& names = stage.model->info().parameters;
  for (const auto& [name, value] : options.truth) {
    bool found = false;
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) {
        (*truth)[i] = value;
        found = true;
      }
    }
    if (!found) {
      *error = "truth names '" + name + "', not a parameter of model " +
               stage.model->info().name;
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

// Noise SD per model output; every compared output needs one.
bool ResolveNoise(const StudyStage& stage, const MonteCarloOptions& options,
                  std::vector<double>* sigma, std::string* error) {
  const ModelInfo& info = stage.model->info();
  sigma->assign(info.outputs.size(), NAN);
  for (const auto& [name, value] : options.noise) {
    const int c = info.OutputIndex(name);
    if (c < 0) {
      *error = "noise names '" + name + "', not an output of model " + info.name;
      return false;
    }
    (*sigma)[c] = value;
  }
  for (const Experiment& e : stage.experiments) {
    for (size_t c = 0; c < info.outputs.size(); ++c) {
      if (e.output_sample_count[c] > 0 && !std::isfinite((*sigma)[c])) {
        *error = "no noise for output '" + info.outputs[c] + "' (compared in experiment '" +
                 e.name + "')";
        return false;
      }
    }
  }
  return true;
}

json Summary(const StudyStage& stage, const std::vector<double>& truth, double z,
             const std::vector<json>& cases) {
  json parameters = json::array();
  int usable = 0;
  for (const json& c : cases) usable += c.value("usable", false) ? 1 : 0;
  for (size_t k = 0; k < stage.free.size(); ++k) {
    const double theta = truth[stage.free[k]];
    std::vector<double> estimates, errors;
    int covered = 0, with_error = 0;
    double squared = 0.0;
    for (const json& c : cases) {
      if (!c.value("usable", false)) continue;
      const double value = NumberOr(c["estimates"][k], NAN);
      const double se = NumberOr(c["std_errors"][k], NAN);
      estimates.push_back(value);
      errors.push_back(se);
      squared += (value - theta) * (value - theta);
      if (std::isfinite(se)) {
        ++with_error;
        covered += std::abs(value - theta) <= z * se ? 1 : 0;
      }
    }
    const MeanSd e = Summarise(estimates), s = Summarise(errors);
    const double coverage = with_error > 0 ? static_cast<double>(covered) / with_error : NAN;
    parameters.push_back(
        {{"name", stage.free_names[k]},
         {"truth", theta},
         {"mean", JsonNumber(e.mean)},
         {"bias", JsonNumber(e.mean - theta)},
         {"bias_percent", JsonNumber(theta != 0.0 ? 100.0 * (e.mean - theta) / theta : NAN)},
         {"bias_std_error", JsonNumber(e.sd / std::sqrt(std::max(1, e.n)))},
         {"sd", JsonNumber(e.sd)},
         {"rmse", JsonNumber(e.n > 0 ? std::sqrt(squared / e.n) : NAN)},
         {"mean_std_error", JsonNumber(s.mean)},
         {"std_error_over_sd", JsonNumber(s.mean / e.sd)},
         {"coverage", JsonNumber(coverage)},
         {"coverage_std_error",
          JsonNumber(with_error > 0 ? std::sqrt(coverage * (1 - coverage) / with_error) : NAN)},
         {"runs_with_std_error", with_error}});
  }
  return {{"runs", cases.size()}, {"usable_runs", usable}, {"parameters", parameters}};
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

bool RunMonteCarloStudy(const RunConfig& config, const MonteCarloOptions& options,
                        unsigned seed, const CaseOptions& execution, json* result,
                        std::string* error, const CaseProgress& progress) {
  const auto start_time = std::chrono::steady_clock::now();
  StudyStage stage;
  if (!PrepareStudyStage(config, options.stage, &stage, error)) return false;
  std::vector<double> truth, sigma;
  if (!ResolveTruth(stage, options, &truth, error) ||
      !ResolveNoise(stage, options, &sigma, error)) {
    *error = "monte_carlo: " + *error;
    return false;
  }
  std::vector<std::vector<double>> clean;
  if (!SimulateSamples(stage, truth, &clean, error)) {
    *error = "monte_carlo: truth: " + *error;
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
    std::mt19937_64 random(CaseSeed(seed, kPart, r));
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<Experiment> experiments = stage.experiments;
    for (size_t e = 0; e < experiments.size(); ++e) {
      for (size_t i = 0; i < experiments[e].samples.size(); ++i) {
        ExperimentSample& s = experiments[e].samples[i];
        s.value = clean[e][i] + sigma[s.output] * normal(random);
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
  json noise = json::object();
  for (const auto& [name, value] : options.noise) noise[name] = value;
  *result = {{"stage", stage.stage->options.name},
             {"runs", options.runs},
             {"noise", noise},
             {"start", options.start_at_truth ? "truth" : "stage"},
             {"confidence", options.confidence},
             {"z", z},
             {"parameters", stage.free_names},
             {"summary", Summary(stage, truth, z, cases)},
             {"noise_model", NoiseModelSummary(options, cases)},
             {"cases", cases},
             {"time_seconds", std::chrono::duration<double>(
                                  std::chrono::steady_clock::now() - start_time)
                                  .count()}};
  return true;
}

std::string MonteCarloText(const json& result) {
  std::string text;
  char line[512];
  const json& summary = result["summary"];
  std::snprintf(line, sizeof(line),
                "Monte Carlo noise study, stage %s: %d runs (%d usable), start %s, %.0f %% "
                "intervals (z = %.3f), %.1f s\n",
                result["stage"].get<std::string>().c_str(), summary["runs"].get<int>(),
                summary["usable_runs"].get<int>(), result["start"].get<std::string>().c_str(),
                100.0 * result["confidence"].get<double>(), result["z"].get<double>(),
                NumberOr(result["time_seconds"], NAN));
  text += line;
  std::snprintf(line, sizeof(line), "  %-12s %13s %13s %11s %12s %12s %9s %14s\n", "parameter",
                "truth", "mean", "bias %", "SD", "mean SE", "SE/SD", "coverage %");
  text += line;
  for (const json& p : summary["parameters"]) {
    std::snprintf(line, sizeof(line), "  %-12s %13.6g %13.6g %11.4f %12.4g %12.4g %9.3f %8.1f +- %.1f\n",
                  p["name"].get<std::string>().c_str(), p["truth"].get<double>(),
                  NumberOr(p["mean"], NAN), NumberOr(p["bias_percent"], NAN),
                  NumberOr(p["sd"], NAN), NumberOr(p["mean_std_error"], NAN),
                  NumberOr(p["std_error_over_sd"], NAN), 100.0 * NumberOr(p["coverage"], NAN),
                  100.0 * NumberOr(p["coverage_std_error"], NAN));
    text += line;
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

#include "engine/study/start_point_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "engine/base/statistics.h"
#include "engine/study/study_stage.h"

namespace vesselid {
namespace {

using nlohmann::json;

constexpr int kStartPointPart = 2;  // CaseSeed part of this study
const char* const kModes[] = {"local", "global"};

std::string SpreadText(double spread) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", spread);
  return text;
}

bool CheckBounds(const StudyStage& stage, const StartPointOptions& options, std::string* error) {
  for (int index : stage.free) {
    const ParameterSpec& spec = stage.specs[index];
    if (!std::isfinite(spec.lower) || !std::isfinite(spec.upper)) {
      *error = "parameter '" + spec.name + "' needs finite bounds to draw starts in";
      return false;
    }
    if (options.spread > 0.0) {
      const auto o = stage.run_optimum.find(spec.name);
      if (o == stage.run_optimum.end() || !(o->second != 0.0)) {
        *error = "parameter '" + spec.name + "': spread needs a non-zero optimum to draw around";
        return false;
      }
    } else if (options.log_sampling && !(spec.lower > 0.0)) {
      *error = "parameter '" + spec.name + "': log sampling needs a positive lower bound";
      return false;
    }
  }
  return true;
}

// Groups optima (usable cases) by parameter agreement, lowest cost first.
json GroupOptima(const StudyStage& stage, double tolerance, std::vector<json>* cases) {
  std::vector<int> order;
  for (size_t i = 0; i < cases->size(); ++i) {
    if ((*cases)[i].value("usable", false)) order.push_back(static_cast<int>(i));
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return (*cases)[a]["cost"].get<double>() < (*cases)[b]["cost"].get<double>();
  });
  std::vector<std::vector<double>> representative;
  json optima = json::array();
  for (int i : order) {
    json& c = (*cases)[i];
    const std::vector<double> values = c["estimates"].get<std::vector<double>>();
    int group = -1;
    for (size_t g = 0; g < representative.size() && group < 0; ++g) {
      bool same = true;
      for (size_t k = 0; k < values.size(); ++k) {
        const double scale =
            std::max(std::abs(representative[g][k]), stage.specs[stage.free[k]].EffectiveScale());
        same = same && std::abs(values[k] - representative[g][k]) <= tolerance * scale;
      }
      if (same) group = static_cast<int>(g);
    }
    if (group < 0) {
      group = static_cast<int>(representative.size());
      representative.push_back(values);
      optima.push_back({{"cost", c["cost"]}, {"estimates", c["estimates"]}, {"local", 0},
                        {"global", 0}});
    }
    c["optimum"] = group;
    optima[group][c["mode"].get<std::string>()] = optima[group][c["mode"].get<std::string>()].get<int>() + 1;
  }
  return optima;
}

json ModeSummary(const StudyStage& stage, const std::string& mode, const std::vector<json>& cases) {
  int runs = 0, usable = 0, best = 0, evaluations = 0;
  std::vector<double> times;
  std::vector<std::vector<double>> estimates(stage.free.size());
  for (const json& c : cases) {
    if (c["mode"] != mode) continue;
    ++runs;
    times.push_back(NumberOr(c["time_seconds"], NAN));
    evaluations += c.value("evaluations", 0);
    if (!c.value("usable", false)) continue;
    ++usable;
    best += c["optimum"].get<int>() == 0 ? 1 : 0;
    for (size_t k = 0; k < stage.free.size(); ++k) {
      estimates[k].push_back(NumberOr(c["estimates"][k], NAN));
    }
  }
  json spread = json::array();
  for (size_t k = 0; k < stage.free.size(); ++k) {
    const MeanSd s = Summarise(estimates[k]);
    const auto [lo, hi] = std::minmax_element(estimates[k].begin(), estimates[k].end());
    spread.push_back({{"name", stage.free_names[k]},
                      {"mean", JsonNumber(s.mean)},
                      {"sd", JsonNumber(s.sd)},
                      {"min", JsonNumber(estimates[k].empty() ? NAN : *lo)},
                      {"max", JsonNumber(estimates[k].empty() ? NAN : *hi)}});
  }
  return {{"mode", mode},
          {"runs", runs},
          {"usable", usable},
          {"reached_best", best},
          {"success_fraction", runs > 0 ? static_cast<double>(best) / runs : 0.0},
          {"global_evaluations", evaluations},
          {"mean_time_seconds", JsonNumber(Summarise(times).mean)},
          {"spread", spread}};
}

}  // namespace

bool RunStartPointStudy(const RunConfig& config, const StartPointOptions& options,
                        unsigned seed, const CaseOptions& execution, json* result,
                        std::string* error, const CaseProgress& progress) {
  const auto start_time = std::chrono::steady_clock::now();
  StudyStage stage;
  // spread: the run's optimum is the centre of the starts.
  if (!PrepareStudyStage(config, options.stage, &stage, error, options.spread > 0.0)) return false;
  if (!CheckBounds(stage, options, error)) {
    *error = "starts: stage '" + stage.stage->options.name + "': " + *error;
    return false;
  }
  GlobalStartOptions global = options.global_given ? options.global : stage.options.global;
  global.threads = 1;  // the cases already fill the cores
  auto run_case = [&](int index) -> json {
    const auto case_start = std::chrono::steady_clock::now();
    const int r = index % options.runs;
    const bool with_global = index >= options.runs;
    std::mt19937_64 random(CaseSeed(seed, kStartPointPart, r));
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<ParameterSpec> specs = stage.specs;
    json start = json::array();
    for (int i : stage.free) {
      ParameterSpec& spec = specs[i];
      const double u = uniform(random);
      if (options.spread > 0.0) {
        // log-uniform within a factor spread of the optimum, cut to the bounds
        const double o = stage.run_optimum.at(spec.name), sign = o > 0.0 ? 1.0 : -1.0;
        double lo = std::abs(o) / options.spread, hi = std::abs(o) * options.spread;
        const double bound_lo = sign > 0 ? spec.lower : -spec.upper;
        const double bound_hi = sign > 0 ? spec.upper : -spec.lower;
        lo = std::max(lo, std::max(bound_lo, 1e-300));
        hi = std::min(hi, bound_hi);
        spec.start = sign * lo * std::pow(hi / lo, u);
      } else {
        spec.start = options.log_sampling ? spec.lower * std::pow(spec.upper / spec.lower, u)
                                          : spec.lower + u * (spec.upper - spec.lower);
      }
      start.push_back(spec.start);
    }
    StageOptions stage_options = stage.options;
    stage_options.use_global_start = with_global;
    stage_options.global = global;
    stage_options.global.seed = static_cast<unsigned>(random() & 0x7FFFFFFF);
    StudySolve solve = SolveStudyStage(stage, stage.experiments, specs, stage_options);
    json c = {{"start_index", r}, {"mode", kModes[with_global ? 1 : 0]}, {"start", start},
              {"usable", solve.usable}};
    if (with_global) c["evaluations"] = solve.summary.global.evaluations;
    if (!solve.usable) {
      c["message"] = solve.message;
    } else {
      json estimates = json::array();
      for (double v : solve.Values(stage)) estimates.push_back(JsonNumber(v));
      c["estimates"] = estimates;
      c["cost"] = solve.summary.local().final_cost;
    }
    c["time_seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - case_start).count();
    return c;
  };
  std::vector<json> cases;
  RunCases(2 * options.runs, run_case, execution, &cases, progress);
  if (!ProcessGroup::Current().root()) {
    *result = nullptr;
    return true;
  }
  json optima = GroupOptima(stage, options.tolerance, &cases);
  json modes = json::array();
  for (const char* mode : kModes) modes.push_back(ModeSummary(stage, mode, cases));
  *result = {{"stage", stage.stage->options.name},
             {"runs", options.runs},
             {"sampling", options.spread > 0.0
                              ? "log within x" + SpreadText(options.spread) + " of the optimum"
                              : options.log_sampling ? "log" : "uniform"},
             {"tolerance", options.tolerance},
             {"global", {{"algorithm", global.algorithm},
                         {"max_evaluations", global.algorithm == "multistart"
                                                 ? global.points
                                                 : global.max_evaluations},
                         {"candidates", global.candidates}}},
             {"parameters", stage.free_names},
             {"optima", optima},
             {"modes", modes},
             {"cases", cases},
             {"time_seconds", std::chrono::duration<double>(
                                  std::chrono::steady_clock::now() - start_time)
                                  .count()}};
  return true;
}

std::string StartPointText(const json& result) {
  std::string text;
  char line[512];
  std::snprintf(line, sizeof(line),
                "Start-point study, stage %s: %d starts drawn %s in the bounds, each solved "
                "locally and with the global start (%s, %d %s), %.1f s\n",
                result["stage"].get<std::string>().c_str(), result["runs"].get<int>(),
                result["sampling"].get<std::string>().c_str(),
                result["global"]["algorithm"].get<std::string>().c_str(),
                result["global"]["max_evaluations"].get<int>(),
                result["global"]["algorithm"] == "multistart" ? "points" : "evaluations",
                NumberOr(result["time_seconds"], NAN));
  text += line;
  for (const json& m : result["modes"]) {
    std::snprintf(line, sizeof(line),
                  "  %-7s reached the best optimum from %3d of %3d starts (%.1f %%), %d failed, "
                  "%.2f s per start\n",
                  m["mode"].get<std::string>().c_str(), m["reached_best"].get<int>(),
                  m["runs"].get<int>(), 100.0 * m["success_fraction"].get<double>(),
                  m["runs"].get<int>() - m["usable"].get<int>(),
                  NumberOr(m["mean_time_seconds"], NAN));
    text += line;
  }
  const json& modes = result["modes"];
  if (modes.size() == 2) {
    std::snprintf(line, sizeof(line),
                  "  global / local: success %.1f %% vs %.1f %%, time per start %.2fx\n",
                  100.0 * modes[1]["success_fraction"].get<double>(),
                  100.0 * modes[0]["success_fraction"].get<double>(),
                  NumberOr(modes[1]["mean_time_seconds"], NAN) /
                      NumberOr(modes[0]["mean_time_seconds"], NAN));
    text += line;
  }
  const std::vector<std::string> names = result["parameters"].get<std::vector<std::string>>();
  text += "  distinct optima (lowest cost first):\n    #  local global          cost";
  for (const std::string& name : names) {
    std::snprintf(line, sizeof(line), " %12s", name.c_str());
    text += line;
  }
  text += "\n";
  int shown = 0;
  for (const json& o : result["optima"]) {
    if (++shown > 10) {
      std::snprintf(line, sizeof(line), "    ... %zu more\n", result["optima"].size() - 10);
      text += line;
      break;
    }
    std::snprintf(line, sizeof(line), "  %3d %6d %6d %13.6e", shown - 1, o["local"].get<int>(),
                  o["global"].get<int>(), o["cost"].get<double>());
    text += line;
    for (const json& v : o["estimates"]) {
      std::snprintf(line, sizeof(line), " %12.6g", NumberOr(v, NAN));
      text += line;
    }
    text += "\n";
  }
  return text;
}

}  // namespace vesselid

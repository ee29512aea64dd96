#include "engine/study/profile_likelihood.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "engine/base/statistics.h"
#include "engine/study/study_stage.h"

namespace vesselid {
namespace {

using nlohmann::json;

// Grid of `points` values over [lo, hi] with the optimum as its middle point.
std::vector<double> Grid(double lo, double center, double hi, int points) {
  const int half = (points - 1) / 2;
  std::vector<double> grid;
  for (int k = half; k >= 1; --k) grid.push_back(center - (center - lo) * k / half);
  grid.push_back(center);
  for (int k = 1; k <= half; ++k) grid.push_back(center + (hi - center) * k / half);
  return grid;
}

// One end of the interval: walking from the optimum (index `middle`) in `step` direction, the
// first crossing of D = threshold, interpolated; open (the last grid value) if none, and
// unsolved too if held values on the way could not be solved (their simulation diverges):
// the interval may end there or beyond, the profile cannot tell.
json IntervalEnd(const std::vector<double>& grid, const std::vector<double>& deviance,
                 int middle, int step, double threshold) {
  int previous = middle;
  bool unsolved = false;
  for (int k = middle + step; k >= 0 && k < static_cast<int>(grid.size()); k += step) {
    if (!std::isfinite(deviance[k])) {
      unsolved = true;
      continue;
    }
    if (deviance[k] > threshold) {
      const double d0 = std::max(0.0, deviance[previous]), d1 = deviance[k];
      const double w = d1 > d0 ? (threshold - d0) / (d1 - d0) : 1.0;
      return {{"value", grid[previous] + w * (grid[k] - grid[previous])}, {"open", false}};
    }
    previous = k;
  }
  return {{"value", grid[previous]}, {"open", true}, {"unsolved", unsolved}};
}

// Profiles of one stage: {stage, optimum, profiles, cases} on rank 0.
bool ProfileStage(const RunConfig& config, const std::string& name, const ProfileOptions& options,
                  const CaseOptions& execution, json* result, std::string* error,
                  const CaseProgress& progress) {
  StudyStage stage;
  if (!PrepareStudyStage(config, name, &stage, error, /*solve=*/true)) return false;
  std::vector<int> profiled;  // positions in stage.free
  for (const std::string& name : options.parameters) {
    const auto at = std::find(stage.free_names.begin(), stage.free_names.end(), name);
    if (at == stage.free_names.end()) {
      *error = "profile: '" + name + "' is not a free parameter of stage '" +
               stage.stage->options.name + "'";
      return false;
    }
    profiled.push_back(static_cast<int>(at - stage.free_names.begin()));
  }
  if (profiled.empty()) {
    for (size_t k = 0; k < stage.free.size(); ++k) profiled.push_back(static_cast<int>(k));
  }

  // The optimum as the run finds it (continuation, global start), polished by a local solve
  // of the study's own problem, which the profiles start from.
  StageOptions local = stage.options;
  local.use_global_start = false;
  StudySolve optimum =
      SolveStudyStage(stage, stage.experiments, stage.specs, local, &stage.run_optimum);
  if (!optimum.usable) {
    *error = "profile: stage '" + stage.stage->options.name + "': " + optimum.message;
    return false;
  }
  const double best_cost = optimum.summary.local().final_cost;
  const int m = optimum.problem->num_residuals(), n = optimum.problem->num_free();
  const double s2 = m > n ? 2.0 * best_cost / (m - n) : NAN;
  const std::vector<double> best = optimum.Values(stage), se = optimum.StdErrors(stage);
  const std::map<std::string, double> best_values = ValuesByName(*optimum.problem);
  // Profiles compare costs with the optimum's, so they keep its noise weights fixed.
  if (stage.noise_weights) {
    stage.experiments = optimum.problem->experiments();
    stage.noise_weights = false;
  }

  std::vector<std::vector<double>> grids;
  for (int k : profiled) {
    const ParameterSpec& spec = stage.specs[stage.free[k]];
    double lo = spec.lower, hi = spec.upper;
    if (std::isfinite(se[k]) && se[k] > 0.0) {
      lo = std::max(lo, best[k] - options.span * se[k]);
      hi = std::min(hi, best[k] + options.span * se[k]);
    }
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
      *error = "profile: '" + spec.name + "' has no standard error and no finite bounds";
      return false;
    }
    grids.push_back(Grid(lo, best[k], hi, options.points));
  }

  local.compute_uncertainty = false;
  const int per = options.points;
  auto run_case = [&](int index) -> json {
    const int j = index / per, g = index % per;
    std::vector<ParameterSpec> specs = stage.specs;
    ParameterSpec& held = specs[stage.free[profiled[j]]];
    held.role = ParameterRole::kFixed;
    held.start = grids[j][g];
    StudySolve solve = SolveStudyStage(stage, stage.experiments, specs, local, &best_values);
    json c = {{"parameter", held.name}, {"value", held.start}, {"usable", solve.usable}};
    if (solve.usable) {
      c["cost"] = solve.summary.local().final_cost;
    } else {
      c["message"] = solve.message;
    }
    return c;
  };
  std::vector<json> cases;
  RunCases(static_cast<int>(profiled.size()) * per, run_case, execution, &cases, progress);
  if (!ProcessGroup::Current().root()) {
    *result = nullptr;
    return true;
  }

  const double threshold = ChiSquare1Quantile(options.confidence);
  const double z = TwoSidedZ(options.confidence);
  json profiles = json::array();
  for (size_t j = 0; j < profiled.size(); ++j) {
    const int k = profiled[j];
    std::vector<double> deviance;
    json points = json::array();
    double lowest = best_cost;
    for (int g = 0; g < per; ++g) {
      const json& c = cases[j * per + g];
      const double cost = c.value("usable", false) ? c["cost"].get<double>() : NAN;
      if (std::isfinite(cost)) lowest = std::min(lowest, cost);
      deviance.push_back(2.0 * (cost - best_cost) / s2);
      points.push_back({{"value", grids[j][g]}, {"cost", JsonNumber(cost)},
                        {"deviance", JsonNumber(deviance.back())}});
    }
    const int middle = (per - 1) / 2;
    json p = {{"parameter", stage.free_names[k]},
              {"estimate", best[k]},
              {"std_error", JsonNumber(se[k])},
              {"linearised", {JsonNumber(best[k] - z * se[k]), JsonNumber(best[k] + z * se[k])}},
              {"lower", IntervalEnd(grids[j], deviance, middle, -1, threshold)},
              {"upper", IntervalEnd(grids[j], deviance, middle, +1, threshold)},
              {"points", points}};
    // A held value with a lower cost than the optimum: the stage's optimum was local.
    if (lowest < best_cost * (1.0 - 1e-9) - 1e-300) {
      p["note"] = "the profile found a lower cost than the optimum (" +
                  std::to_string(lowest) + " < " + std::to_string(best_cost) +
                  "): the stage's solve ended in a local minimum";
    }
    profiles.push_back(p);
  }
  *result = {{"stage", stage.stage->options.name},
             {"optimum",
              {{"cost", best_cost}, {"residuals", m}, {"free", n}, {"residual_variance", s2}}},
             {"profiles", profiles},
             {"cases", cases}};
  return true;
}

}  // namespace

bool RunProfileLikelihood(const RunConfig& config, const ProfileOptions& options,
                          const CaseOptions& execution, json* result, std::string* error,
                          const CaseProgress& progress) {
  const auto start_time = std::chrono::steady_clock::now();
  std::vector<std::string> names = options.stages;
  if (names.empty()) names.push_back("");  // the run's last output-error stage
  json stages = json::array();
  for (const std::string& name : names) {
    json stage;
    if (!ProfileStage(config, name, options, execution, &stage, error, progress)) return false;
    stages.push_back(std::move(stage));
  }
  if (!ProcessGroup::Current().root()) {
    *result = nullptr;
    return true;
  }
  *result = {{"confidence", options.confidence},
             {"threshold", ChiSquare1Quantile(options.confidence)},
             {"stages", stages},
             {"time_seconds", std::chrono::duration<double>(
                                  std::chrono::steady_clock::now() - start_time)
                                  .count()}};
  return true;
}

std::string ProfileText(const json& result) {
  std::string text;
  char line[512];
  std::snprintf(line, sizeof(line),
                "Profile likelihood: %.0f %% intervals where 2 dF / s^2 <= %.3f, %.1f s\n",
                100.0 * result["confidence"].get<double>(), result["threshold"].get<double>(),
                NumberOr(result["time_seconds"], NAN));
  text += line;
  auto end = [](const json& e, bool lower) {
    char s[64];
    const char* mark = !e["open"].get<bool>()         ? ""
                       : e.value("unsolved", false) ? "?"
                       : lower                      ? "<"
                                                    : ">";
    std::snprintf(s, sizeof(s), "%s%.6g", mark, e["value"].get<double>());
    return std::string(s);
  };
  for (const json& stage : result["stages"]) {
    std::snprintf(line, sizeof(line), "  stage %s (cost %.6e, %d residuals, %d unknowns):\n",
                  stage["stage"].get<std::string>().c_str(), stage["optimum"]["cost"].get<double>(),
                  stage["optimum"]["residuals"].get<int>(), stage["optimum"]["free"].get<int>());
    text += line;
    std::snprintf(line, sizeof(line), "    %-12s %13s %12s %27s %27s\n", "parameter", "estimate",
                  "SE", "profile interval", "linearised interval");
    text += line;
    for (const json& p : stage["profiles"]) {
      const std::string profile = "[" + end(p["lower"], true) + ", " + end(p["upper"], false) + "]";
      char linear[96];
      std::snprintf(linear, sizeof(linear), "[%.6g, %.6g]", NumberOr(p["linearised"][0], NAN),
                    NumberOr(p["linearised"][1], NAN));
      std::snprintf(line, sizeof(line), "    %-12s %13.6g %12.4g %27s %27s\n",
                    p["parameter"].get<std::string>().c_str(), p["estimate"].get<double>(),
                    NumberOr(p["std_error"], NAN), profile.c_str(), linear);
      text += line;
      if (p.contains("note")) text += "      note: " + p["note"].get<std::string>() + "\n";
    }
  }
  text += "  (\"<\" / \">\": the deviance stays below the threshold to the end of the grid; \"?\": held\n"
          "  values beyond could not be solved, e.g. their simulation diverges)\n";
  return text;
}

}  // namespace vesselid

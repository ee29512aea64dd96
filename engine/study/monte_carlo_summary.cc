#include "engine/study/monte_carlo_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/base/json_number.h"
#include "engine/base/statistics.h"

namespace vesselid {

using nlohmann::json;

json MonteCarloSummary(const MonteCarloTruth& truth, double z, const std::vector<json>& cases) {
  json parameters = json::array();
  int usable = 0;
  for (const json& c : cases) usable += c.value("usable", false) ? 1 : 0;
  for (size_t k = 0; k < truth.names.size(); ++k) {
    const double theta = truth.values[k];
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
    json p = {
        {"name", truth.names[k]},
        {"truth", theta},
        {"mean", JsonNumber(e.mean)},
        {"bias", JsonNumber(e.mean - theta)},
        {"bias_percent", JsonNumber(theta != 0.0 ? 100.0 * (e.mean - theta) / theta : NAN)},
        {"bias_std_error", JsonNumber(e.sd / std::sqrt(std::max(1, e.n)))},
        {"bias_over_std_error", JsonNumber((e.mean - theta) / s.mean)},
        {"sd", JsonNumber(e.sd)},
        {"rmse", JsonNumber(e.n > 0 ? std::sqrt(squared / e.n) : NAN)},
        {"mean_std_error", JsonNumber(s.mean)},
        {"std_error_over_sd", JsonNumber(s.mean / e.sd)},
        {"coverage", JsonNumber(coverage)},
        {"coverage_std_error",
         JsonNumber(with_error > 0 ? std::sqrt(coverage * (1 - coverage) / with_error) : NAN)},
        {"runs_with_std_error", with_error}};
    if (!truth.stage_std_errors.empty()) {
      p["stage_std_error"] = JsonNumber(truth.stage_std_errors[k]);
      p["sd_over_stage_std_error"] = JsonNumber(e.sd / truth.stage_std_errors[k]);
    }
    parameters.push_back(p);
  }
  return {{"runs", cases.size()}, {"usable_runs", usable}, {"parameters", parameters}};
}

std::vector<std::string> MonteCarloNotes(const json& summary, double confidence, bool bootstrap,
                                         const std::vector<json>& cases) {
  std::vector<std::string> notes;
  char line[512];
  const int runs = summary["runs"].get<int>(), usable = summary["usable_runs"].get<int>();
  if (usable < runs) {
    std::string first;
    for (const json& c : cases) {
      if (!c.value("usable", false) && first.empty()) first = c.value("message", "");
    }
    std::snprintf(line, sizeof(line), "%d of %d runs unusable (left out of the summary; first: %s)",
                  runs - usable, runs, first.c_str());
    notes.push_back(line);
  }
  for (const json& p : summary["parameters"]) {
    const std::string name = p["name"].get<std::string>();
    const double coverage = NumberOr(p["coverage"], NAN);
    const int n = p["runs_with_std_error"].get<int>();
    const double ratio = NumberOr(p["std_error_over_sd"], NAN);
    // Coverage off the nominal by more than 2.5 binomial standard errors of the nominal.
    const double band = 2.5 * std::sqrt(confidence * (1.0 - confidence) / std::max(1, n));
    if (n >= 10 && std::abs(coverage - confidence) > band) {
      std::snprintf(line, sizeof(line),
                    "%s: the reported %.0f %% intervals covered the truth in %.0f %% of %d runs "
                    "(mean SE / SD %.2f): they are too %s",
                    name.c_str(), 100.0 * confidence, 100.0 * coverage, n, ratio,
                    coverage < confidence ? "narrow" : "wide");
      notes.push_back(line);
    }
    const double bias = NumberOr(p["bias"], NAN), bias_se = NumberOr(p["bias_std_error"], NAN);
    const double in_se = NumberOr(p["bias_over_std_error"], NAN);
    if (std::abs(bias) > 3.0 * bias_se && std::abs(in_se) > 0.25) {
      std::snprintf(line, sizeof(line),
                    "%s: biased by %.3g %% (%.2f reported SE, %.1f times its own standard "
                    "error)%s",
                    name.c_str(), NumberOr(p["bias_percent"], NAN), in_se, bias / bias_se,
                    bootstrap ? " at the estimate" : "");
      notes.push_back(line);
    }
    // Bootstrap SD against the stage's SE beyond the sampling noise of an SD,
    // 1 / sqrt(2 (N - 1)) relative, and by more than 25 %.
    const double sd_ratio = NumberOr(p.value("sd_over_stage_std_error", json()), NAN);
    const double noise = 3.0 / std::sqrt(2.0 * std::max(1, usable - 1));
    if (std::isfinite(sd_ratio) && usable >= 10 &&
        std::abs(std::log(sd_ratio)) > std::max(std::log(1.25), std::log1p(noise))) {
      std::snprintf(line, sizeof(line),
                    "%s: bootstrap SD %.4g is %.2f times the stage's reported SE %.4g: the run's "
                    "intervals are too %s",
                    name.c_str(), NumberOr(p["sd"], NAN), sd_ratio,
                    NumberOr(p["stage_std_error"], NAN), sd_ratio > 1.0 ? "narrow" : "wide");
      notes.push_back(line);
    }
  }
  return notes;
}

}  // namespace vesselid

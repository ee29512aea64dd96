#include "engine/output/selection_report.h"

#include <cmath>
#include <cstdio>

#include "engine/base/format_numbers.h"
#include "engine/base/json_number.h"

namespace vesselid {
namespace {

// A fit % as the table shows it: two decimals, or three digits where a diverged prediction
// made it astronomically negative (it would otherwise print as a 60-digit number).
std::string FitPercentText(double value) {
  return FormatFinite(std::abs(value) < 1e5 ? "%.2f" : "%.3g", value);
}

// A count where it was counted, else null (an unusable candidate's, a horizon not predicted).
nlohmann::json Counted(bool counted, int value) {
  return counted ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

const char kSelectionDefinitions[] =
    "each candidate fitted without a fold's runs and those runs predicted free-running (each "
    "estimating its own per-run parameters and initial states with the shared ones held); "
    "score = mean over folds of the fold's mean fit %; SE = SD over folds / sqrt(folds); the "
    "choice: the simplest candidate (fewest shared parameters) whose score is within one SE of "
    "the best. AIC = n ln(RSS/n) + 2k and BIC = n ln(RSS/n) + k ln n of the scored outputs' "
    "residuals in the fit on every run, k = shared parameters + per-run values + initial "
    "states. BIC_L = 2 (-log L) + k' ln N of the same fit's likelihood over its compared "
    "outputs (a filter-error stage's innovations'; output error's Gaussian residuals with "
    "their variances estimated), k' = k + the disturbance's parameters (output error: a "
    "variance per output): candidates with and without a disturbance model scored the same "
    "way. Filter-error candidates: their held-out runs also predicted through the filter, "
    "k samples and one step ahead (fit %, mean over folds).";

nlohmann::json SelectionToJson(const SelectionResult& s) {
  nlohmann::json candidates = nlohmann::json::array();
  for (const SelectionCandidate& c : s.candidates) {
    nlohmann::json outputs = nlohmann::json::array();
    for (const SelectionOutputScore& o : c.outputs) {
      outputs.push_back({{"output", o.output},
                         {"unit", o.unit},
                         {"fit_percent", JsonNumber(o.fit_percent)},
                         {"fit_sd", JsonNumber(o.fit_sd)},
                         {"rmse", JsonNumber(o.rmse)}});
    }
    nlohmann::json folds = nlohmann::json::array();
    for (double f : c.fold_scores) folds.push_back(JsonNumber(f));
    candidates.push_back({{"name", c.name},
                          {"model", c.model},
                          {"usable", c.usable},
                          {"message", c.message},
                          {"shared_parameters", c.shared_parameters},
                          {"per_run_values", c.per_run_values},
                          {"initial_states", c.initial_states},
                          {"score", JsonNumber(c.score)},
                          {"score_se", JsonNumber(c.score_se)},
                          {"fold_scores", folds},
                          {"outputs", outputs},
                          {"samples", c.samples},
                          {"rss", JsonNumber(c.rss)},
                          {"aic", JsonNumber(c.aic)},
                          {"bic", JsonNumber(c.bic)},
                          {"disturbance", c.disturbance},
                          {"negative_log_likelihood", JsonNumber(c.negative_log_likelihood)},
                          {"likelihood_unknowns", Counted(c.usable, c.likelihood_unknowns)},
                          {"likelihood_samples", Counted(c.usable, c.likelihood_samples)},
                          {"likelihood_bic", JsonNumber(c.likelihood_bic)},
                          {"prediction_steps", Counted(c.prediction_steps > 0, c.prediction_steps)},
                          {"k_step_fit_percent", JsonNumber(c.k_step_fit_percent)},
                          {"one_step_fit_percent", JsonNumber(c.one_step_fit_percent)},
                          {"within_one_se", c.within_one_se}});
  }
  auto name = [&](int i) {
    return i >= 0 ? nlohmann::json(s.candidates[i].name) : nlohmann::json(nullptr);
  };
  return {{"method", s.method},   {"folds", s.folds},
          {"outputs", s.outputs}, {"candidates", candidates},
          {"best", name(s.best)}, {"chosen", name(s.chosen)},
          {"reason", s.reason},   {"likelihoods_comparable", s.likelihoods_comparable},
          {"likelihood_note", s.likelihood_note},
          {"time_seconds", s.time_seconds}};
}

std::string SelectionText(const SelectionResult& s) {
  if (s.empty()) return "";
  std::string out = "structure selection, " + s.method + " over " + std::to_string(s.folds.size()) +
                    " folds, scored on " +
                    (s.outputs.empty() ? std::string("-") : s.outputs.front());
  for (size_t i = 1; i < s.outputs.size(); ++i) out += ", " + s.outputs[i];
  out += " (" + std::string(kSelectionDefinitions) + ")\n";
  char line[1024];
  bool filtered = false;  // a candidate predicted through its filter
  for (const SelectionCandidate& c : s.candidates) filtered = filtered || c.prediction_steps > 0;
  std::snprintf(line, sizeof(line), "  %-22s %-28s %7s %7s %7s %7s %16s %12s %12s %12s%s  %s\n",
                "candidate", "model", "shared", "per-run", "states", "fit %", "+- SE", "AIC", "BIC",
                "BIC_L", filtered ? "        k-step %  1-step %" : "", "per output: fit % (SD) RMSE");
  out += line;
  for (size_t i = 0; i < s.candidates.size(); ++i) {
    const SelectionCandidate& c = s.candidates[i];
    std::string per_output;
    for (const SelectionOutputScore& o : c.outputs) {
      per_output += o.output + " " + FitPercentText(o.fit_percent) + " (" +
                    FitPercentText(o.fit_sd) + ") " + FormatFinite("%.3g", o.rmse) +
                    (o.unit.empty() ? "" : " " + o.unit) + "  ";
    }
    if (!c.disturbance.empty()) per_output += "noise: " + c.disturbance + "  ";
    if (!c.usable) per_output = "not scored: " + c.message;
    std::string through_filter;
    if (filtered) {
      // k beside its fit: candidates may predict different horizons.
      char cells[96];
      const std::string k_step =
          c.prediction_steps > 0
              ? FitPercentText(c.k_step_fit_percent) + " (k " + std::to_string(c.prediction_steps) + ")"
              : "-";
      std::snprintf(cells, sizeof(cells), "  %14s  %8s", k_step.c_str(),
                    FitPercentText(c.one_step_fit_percent).c_str());
      through_filter = cells;
    }
    const std::string mark = static_cast<int>(i) == s.chosen ? "  <- chosen"
                             : c.within_one_se               ? "  (within 1 SE)"
                                                             : "";
    std::snprintf(line, sizeof(line), "  %-22s %-28s %7d %7d %7d %7s %16s %12s %12s %12s%s  %s%s\n",
                  c.name.c_str(), c.model.c_str(), c.shared_parameters, c.per_run_values,
                  c.initial_states, FitPercentText(c.score).c_str(),
                  ("+- " + FitPercentText(c.score_se)).c_str(),
                  FormatFinite("%.1f", c.aic).c_str(), FormatFinite("%.1f", c.bic).c_str(),
                  FormatFinite("%.1f", c.likelihood_bic).c_str(), through_filter.c_str(),
                  per_output.c_str(), mark.c_str());
    out += line;
  }
  out += "  folds:";
  for (size_t f = 0; f < s.folds.size(); ++f) {
    out += (f == 0 ? " [" : ", [");
    for (size_t r = 0; r < s.folds[f].size(); ++r) out += (r ? " " : "") + s.folds[f][r];
    out += "]";
  }
  out += "\n  fold scores:";
  for (const SelectionCandidate& c : s.candidates) {
    out += "\n    " + c.name + ":";
    for (double f : c.fold_scores) out += " " + FitPercentText(f);
  }
  if (!s.likelihood_note.empty()) out += "\n  note: " + s.likelihood_note;
  if (!s.likelihoods_comparable) {
    out += "\n  note: the candidates' likelihoods cover different outputs or samples: BIC_L does "
           "not compare them";
  }
  out += "\n  chosen: " + s.reason + "\n";
  return out;
}

}  // namespace vesselid

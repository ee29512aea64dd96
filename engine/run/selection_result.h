// Model-structure selection by cross-validation over runs (`vesselid select`,
// engine/select/selection.h) as plain data: the folds, each candidate's scores and the choice,
// which results.json, report.txt and report.html of the chosen candidate's run show.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace vesselid {

// A candidate's cross-validated prediction of one scored output.
struct SelectionOutputScore {
  std::string output;
  std::string unit;  // as the records give it ("deg", "m")
  double fit_percent = std::numeric_limits<double>::quiet_NaN();  // mean over folds
  double fit_sd = std::numeric_limits<double>::quiet_NaN();       // SD over folds
  double rmse = std::numeric_limits<double>::quiet_NaN();         // mean over folds
};

struct SelectionCandidate {
  std::string name;
  std::string model;  // the model's name (nomoto_norrbin_n1_speed, mmg)
  bool usable = false;
  std::string message;  // why not usable (a fold's run failed), or empty
  // Estimated on all the runs: shared parameters, per-run values (a bias per run), initial
  // states; `complexity` = shared parameters, the one-standard-error rule's measure.
  int shared_parameters = 0, per_run_values = 0, initial_states = 0;
  int complexity = 0;
  // Per fold: the mean over its held-out runs and the scored outputs of the free-run fit %.
  std::vector<double> fold_scores;
  double score = std::numeric_limits<double>::quiet_NaN();     // mean of fold_scores
  double score_se = std::numeric_limits<double>::quiet_NaN();  // SD / sqrt(folds)
  std::vector<SelectionOutputScore> outputs;
  // The fit on every run: residual samples of the scored outputs, their sum of squares (in
  // the records' units), and the Gaussian information criteria of those residuals,
  // AIC = n ln(RSS/n) + 2 k, BIC = n ln(RSS/n) + k ln n, k = every estimated number.
  int samples = 0;
  double rss = std::numeric_limits<double>::quiet_NaN();
  double aic = std::numeric_limits<double>::quiet_NaN();
  double bic = std::numeric_limits<double>::quiet_NaN();
  bool within_one_se = false;  // score >= best score - best's score_se
  // The likelihood of the fit on every run, so that candidates with and without a disturbance
  // model (`noise:`) are scored the same way: a filter-error stage's innovations' -log L, an
  // output-error stage's Gaussian one, sum over its compared outputs o of
  // n_o/2 (ln(2 pi RSS_o/n_o) + 1) (the residual variances estimated, one unknown each);
  // BIC_L = 2 (-log L) + k ln N, k = every estimated number, the disturbance's included,
  // N = likelihood_samples. Comparable where the candidates compare the same samples.
  std::string disturbance;  // the last stage's disturbance in words; "" for output error
  double negative_log_likelihood = std::numeric_limits<double>::quiet_NaN();
  int likelihood_unknowns = 0, likelihood_samples = 0;
  double likelihood_bic = std::numeric_limits<double>::quiet_NaN();
  // A filter-error candidate's held-out runs predicted through its filter (filter_prediction.h),
  // the mean over folds of each fold's mean over its runs and the scored outputs: k samples
  // ahead of the filtered state and one step ahead. NaN for output error.
  int prediction_steps = 0;
  double k_step_fit_percent = std::numeric_limits<double>::quiet_NaN();
  double one_step_fit_percent = std::numeric_limits<double>::quiet_NaN();
};

struct SelectionResult {
  std::string method;                           // "leave-one-run-out" or "<k>-fold by run"
  std::vector<std::vector<std::string>> folds;  // the runs each fold holds out
  std::vector<std::string> outputs;             // the scored outputs
  std::vector<SelectionCandidate> candidates;
  int best = -1, chosen = -1;  // indexes into candidates
  std::string reason;          // the choice, stated
  double time_seconds = 0.0;
  // Whether the usable candidates' likelihoods cover the same samples (comparable BIC_L).
  bool likelihoods_comparable = false;
  // Where an output-error candidate holds its runs' starts at their first samples beside a
  // filter-error candidate (which takes them as measured, with their noise): what BIC_L then
  // also weighs. Empty otherwise.
  std::string likelihood_note;
  bool empty() const { return candidates.empty(); }
};

}  // namespace vesselid

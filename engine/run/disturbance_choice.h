// `noise: {method: auto}`: the disturbance model a stage keeps (model/disturbance.h). Output
// error first; where its residuals are white nothing more is tried. Otherwise the filter-error
// candidates in order of complexity, each solved from output error's estimate:
//   white           the filter with white noise only (the record's start not held exact)
//   ar1             AR(1) noise (with a white part) on each output whose residuals are coloured
//   process         white process noise on each state whose equation the inputs drive
//   ar1 + process   both
// and the one of least BIC = 2 (-log L) + k log N (N samples, k free unknowns) is kept; output
// error's -log L is that of its residuals under its maximum-likelihood sigma per output,
// sum_j N_j / 2 (log(2 pi sigma_j^2) + 1). The report names every candidate's score and keeps
// output error's estimates beside the chosen ones.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "engine/model/disturbance.h"
#include "engine/run/disturbance_report.h"
#include "engine/run/run_config.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/residual_analysis.h"
#include "engine/solve/stage.h"

namespace vesselid {

// Combined standard errors sqrt(SE_oe^2 + SE_fe^2) beyond which auto's note says the chosen
// disturbance model's ship estimates disagree with output error's: the noise classes of the
// independent corpus reach 6.4, its structure classes 9.5-56, strong gusts 16 (docs/models.md).
inline constexpr double kStructureDisagreement = 10.0;

struct DisturbanceCandidate {
  std::string name;  // "output_error", "white", "ar1(psi)", "process(eta2)", ...
  DisturbanceSpec spec;
  bool solved = false;
  std::string why;  // why not solved
  double negative_log_likelihood = 0.0;
  int unknowns = 0;
  double bic = 0.0;
  int iterations = 0;  // the solver's, over every start and pass of its solve
};

// The candidates for `model` whose output-error residuals are `residuals` (coloured outputs get
// an AR(1)); the first is output error itself.
std::vector<DisturbanceCandidate> DisturbanceCandidates(const ModelHandle& model,
                                                        const OutputErrorProblem& solved,
                                                        const std::vector<ResidualAnalysis>& residuals);

// A filter-error stage's uncertainty: `auto` is the Hessian (the likelihood's Fisher
// information, its own scale: the innovations it assumes white are checked by the verdict), and
// no input noise refits (the inputs' noise is in the process noise).
UncertaintyOptions FilterErrorUncertainty(UncertaintyOptions options);

// -log L of an output-error problem at its current values under the maximum-likelihood sigma
// per output (NaN if a simulation diverges).
double OutputErrorNegativeLogLikelihood(const OutputErrorProblem& problem);

// Under the filter-error method a stage whose uncertainty the config left to `auto` gets the
// likelihood's Fisher information (FilterErrorUncertainty): says so in `u`'s method_reason,
// where it would say "configured".
void NameFilterErrorUncertainty(const UncertaintyOptions& configured, Uncertainty* u);

// The stage's disturbance report (disturbance_report.h) for results.json: empty under output
// error unless `spec` asked for auto; `candidates` as ChooseDisturbance left them (the chosen:
// the least BIC of the solved, as it chose).
DisturbanceReport ReportDisturbance(const DisturbanceSpec& spec, const OutputErrorProblem& problem,
                                    const Uncertainty& uncertainty,
                                    const std::vector<DisturbanceCandidate>& candidates);

// Chooses for a solved output-error stage: on a filter-error win, *problem and *summary are
// replaced by the chosen candidate's, solved from output error's estimate. Notes name every
// candidate's BIC and output error's estimates. False only on an error of the choice itself.
bool ChooseDisturbance(const StageConfig& stage, const StageOptions& options,
                       const std::vector<ResidualAnalysis>& residuals,
                       std::unique_ptr<OutputErrorProblem>* problem, StageSummary* summary,
                       std::vector<DisturbanceCandidate>* candidates, std::string* error);

}  // namespace vesselid

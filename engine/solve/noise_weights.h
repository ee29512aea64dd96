// Per-channel noise model (`weights: noise`): maximum likelihood for Gaussian output noise
// of unknown variance sigma_c^2 per output channel c. For fixed sigmas the likelihood is the
// output-error cost with every sample of channel c weighted 1/sigma_c; for fixed parameters
// its maximum over sigma_c is the channel's mean squared (unweighted) residual, pooled over
// the stage's experiments and corrected for the free unknowns' share of the samples:
//   sigma_c^2 = SSE_c / (m_c - n m_c / m) = (SSE_c / m_c) m / (m - n)
// (m samples, m_c of channel c, n free unknowns). The stage alternates the two: solved with
// the data's noise levels (or its configured weights), then re-solved from its estimate with
// w = 1/sigma_c until every sigma changes by less than kNoiseTarget (relative), at most
// kNoiseMaxResolves times.
// At the fixed point the weighted residuals have unit variance per channel, so the
// covariance's s^2 = 2F / (m - n) is ~1 and the standard errors are those of the noise model.
#pragma once

#include <string>
#include <vector>

#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"

namespace vesselid {

// Settled: no sigma changed by 5 % in the last re-solve; within that the weights (and the
// estimate) move by less. The re-solves go on, within kNoiseMaxResolves, to 1 %: at 5 % the
// end point depended on the path (far starts of the 3-DOF benchmark stopped at other weights
// and estimates 0.02-0.09 standard errors apart); they start at the optimum and take a few
// iterations (docs/benchmarks.md).
inline constexpr double kNoiseTolerance = 0.05;
inline constexpr double kNoiseTarget = 0.01;
inline constexpr int kNoiseMaxResolves = 3;

// A stage's noise model as reported. `method` "noise" when estimated (active), "given" for
// the configured weights (nothing else set then).
struct NoiseModel {
  std::string method = "given";
  int iterations = 0;      // re-solves with noise weights
  bool converged = false;  // the last re-solve changed no sigma by kNoiseTolerance or more
  std::vector<std::string> outputs;  // compared outputs, model order
  std::vector<double> sigma;         // per output, physical units (radians for angles)
  std::vector<int> samples;          // per output, over the stage's experiments

  bool active() const { return method == "noise"; }
  // Per model output (`num_outputs`): 1/sigma for the compared ones, NaN elsewhere.
  std::vector<double> Weights(const ModelInfo& info) const;
};

// The first solve's weights under `weights: noise`: w_c = 1/sigma_c with sigma_c each compared
// channel's noise level as the data alone show it (second differences, Experiment::NoiseLevel),
// pooled over the experiments, sigma_c^2 = sum_e P_ce / sum_e m_ce. Unit weights make metres
// outweigh a heading in radians by its noise ratio, and Levenberg-Marquardt crawls along the
// valley that leaves (docs/benchmarks.md, the MMG campaign). False, the weights unchanged,
// when a compared channel has no level (fewer than three samples, or an exact signal).
bool SetDataNoiseWeights(OutputErrorProblem* problem);

// sigma per compared output from the fit at the problem's current values (`fits` as
// EvaluateFit made them). False (with `error`) when a channel has no residual to estimate it
// from (no samples, or an exact fit).
bool EstimateChannelNoise(const OutputErrorProblem& problem, const std::vector<ExperimentFit>& fits,
                          NoiseModel* noise, std::string* error);

// Iterates the noise weights from a solved problem (`summary` its RunStage summary): each
// re-solve starts from the current values without global start and replaces `summary`. A
// model that did not settle is named in a note ("noise weights: ..."). False if a re-solve
// fails (summary->message says why) or no sigma can be estimated (`summary` unchanged, the
// reason in a note; noise->method stays "given").
bool IterateNoiseWeights(const StageOptions& options, OutputErrorProblem* problem,
                         StageSummary* summary, NoiseModel* noise);

}  // namespace vesselid

// Errors in variables by default (`uncertainty: {input_noise: auto}`). Output error simulates
// with the measured inputs, so white noise on a logged rudder enters every simulated output
// (psi' = r integrates its slow part into a random walk) and moves the estimate by more than
// the Hessian's or the HAC's covariance allows: on the independent corpus (tests/corpus), K
// ended 3-8 of those SEs from the truth on records whose residuals looked white.
//
// Where an experiment's input carries white noise (WhiteInputNoise, data/white_noise.h)
// and is not declared under the experiment's `input_noise:` (a latent input), the stage is
// solved again `input_noise_runs` times (default 12) from its estimate, each time with fresh
// white noise of the input's SD added to that input (drawn at the simulation's nodes,
// interpolated linearly over each step), and
//   Var_i = Var_hessian,i + Var_input,i,   Var_input the replicates' sample variances:
// to first order the estimate moves by A e_u for the input noise e_u, and the replicates'
// moves A e'_u have the same covariance. The correlations stay the Hessian's (each row and
// column scaled by sqrt(Var_i / Var_hessian,i)): a dozen refits estimate a variance to about
// +-40 % but a correlation far worse. Where `auto` had chosen the HAC (coloured residuals),
// the HAC is kept only if wider than that sum (geometric mean of the SE ratios): the colour is
// then more than the input noise's, which the HAC would otherwise count a second time. A
// configured sandwich_hac or bootstrap is left as it is: both see the noise's residuals.
// The same replicates measure how much of the residuals the input noise makes: a replicate's
// simulated outputs move from the stage's by what the added noise leaves after the refit,
// of mean square c per experiment and output (the cross term with the stage's own residuals,
// large and random over a record's few slow swings, is left out this way). c of one record
// varies widely (a random walk has few degrees of freedom): its 99 % quantile over the refits
// (scaled chi-square with their mean and variance) over ms_0 is the largest share of the
// stage's residual power that the input's noise can explain, not missing
// structure (the coloured_residuals rule reads it, residual_findings.h).
#pragma once

#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"

namespace vesselid {

// Fewest replicates `uncertainty: {input_noise_runs: N}` takes, and the share of them that
// must solve for the spread to be used.
inline constexpr int kMinInputNoiseRuns = 5;
inline constexpr double kMinInputNoiseSolved = 0.5;
// Iterations of each refit: started at the optimum, the first step is the Gauss-Newton move
// A e' whose spread is wanted, the second follows the nonlinearity. Full solves gave the same
// standard errors to 2-3 digits on the corpus's Nomoto fits; the KVLCC2 campaign's stage
// costs 1.2x its solve instead of 1.6x.
inline constexpr int kInputNoiseIterations = 2;
// Beyond these the refits are not made (a note says so; `input_noise` warns as with `off`):
// two copies of the problem solve at once, and a campaign of thousands of segments would
// double the run's memory and cost minutes (50 000 segments: over ten minutes).
inline constexpr int kMaxInputNoiseExperiments = 200;
inline constexpr double kMaxInputNoiseSamples = 2e6;

// Adds the input noise's part to summary->uncertainty at the solved problem's values (and
// records what was done in it and in summary->notes); nothing when no experiment has a noisy
// exact input, the stage computes no uncertainty, or options turn it off.
void AddInputNoiseSpread(const RunConfig& config, TrajectoryCache* cache,
                         const StageOptions& options, const OutputErrorOptions& problem_options,
                         OutputErrorProblem* solved, StageSummary* summary);

}  // namespace vesselid

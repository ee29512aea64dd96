// Bootstrap covariance of a solved output-error stage (`uncertainty: {method: ...}`):
//   block_bootstrap       y* = y_fit + e*, e* the residuals (y - y_fit) resampled in blocks of
//                         consecutive time nodes (all channels of a node together) drawn with
//                         replacement within each experiment: serial correlation inside a
//                         block is kept;
//   experiment_bootstrap  experiments/segments drawn with replacement; one drawn k times
//                         weighs k (its sample and prior weights times sqrt(k); k = 0: 0).
// Each replicate is solved locally from the estimate on its own OutputErrorProblem, in
// parallel (ParallelFor, replicate r seeded by CaseSeed: the result does not depend on the
// threads); Cov = the sample covariance of the replicates' estimates (physical units),
// SE = their standard deviation. The stage's Hessian standard errors are kept beside.
#pragma once

#include <string>

#include "engine/solve/output_error_problem.h"
#include "engine/solve/stage.h"

namespace vesselid {

// Fewest experiments/segments experiment_bootstrap resamples.
inline constexpr int kMinBootstrapExperiments = 5;
// Share of failed replicates above which a warning is given.
inline constexpr double kBootstrapFailureWarning = 0.1;

// The refusal of experiment_bootstrap for stage `stage` with `count` experiments.
std::string ExperimentBootstrapRefusal(const std::string& stage, int count);

// Replaces summary->uncertainty by options.uncertainty's bootstrap estimate at the problem's
// current (solved) values. Where the bootstrap cannot be done (too few experiments, too few
// replicates solved), summary->uncertainty is kept and a bootstrap finding says why; failed
// replicates above kBootstrapFailureWarning are a bootstrap finding too.
void BootstrapStageUncertainty(const StageOptions& options, const OutputErrorOptions& problem_options,
                               OutputErrorProblem* solved, StageSummary* summary);

}  // namespace vesselid

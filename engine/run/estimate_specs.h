// The model parameters of a solved stage as specifications to build the same problem again
// on other data (a refinement, a bootstrap replicate): each parameter starts at its estimate
// and keeps its role, bounds and scale; a shared parameter held fixed stays fixed.
#pragma once

#include <memory>
#include <vector>

#include "engine/solve/output_error_problem.h"
#include "engine/solve/parameter.h"
#include "engine/solve/stage.h"

namespace vesselid {

std::vector<ParameterSpec> EstimateSpecs(const OutputErrorProblem& solved);

// The stage's options for such a replicate solve: local from the estimate (no global start),
// no uncertainty, one thread (the replicates are the parallel work), no progress reports.
StageOptions ReplicateOptions(const StageOptions& options);

// The problem of `solved` built on `experiments` from `specs` (EstimateSpecs), set to the
// estimate and solved with `options` (ReplicateOptions); null when it cannot be built or
// solved.
std::unique_ptr<OutputErrorProblem> SolveReplicate(const OutputErrorProblem& solved,
                                                   std::vector<Experiment> experiments,
                                                   const std::vector<ParameterSpec>& specs,
                                                   const OutputErrorOptions& problem_options,
                                                   const StageOptions& options);

// The problem of `solved` with `problem_options` built on `experiments` from its estimate (its
// variables carried by name, noise parameters too where both have them) and solved locally
// from there (no global start, the near-optimum radius). The earlier `summary`'s notes come
// first in the new one, and its findings but narrow_intervals (the new solve finds its own
// intervals); null with `error` when it cannot be built or solved.
std::unique_ptr<OutputErrorProblem> RefineFromEstimate(const OutputErrorProblem& solved,
                                                       std::vector<Experiment> experiments,
                                                       const OutputErrorOptions& problem_options,
                                                       StageOptions options,
                                                       StageSummary* summary, std::string* error);

}  // namespace vesselid

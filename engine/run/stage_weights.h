// How an output-error stage weighs its channels (StageConfig::weights):
//   given: the experiments' configured `weights:` (relative, per output), each experiment
//          normalised by its length unless normalize_by_length: false;
//   noise: the per-channel noise model (noise_weights.h), every sample weighted 1/sigma_c of
//          its channel. Maximum likelihood weighs each sample alike, so experiments weigh by
//          their samples: length normalisation is off unless the stage sets
//          normalize_by_length: true itself. The first solve weighs by the data's own noise
//          levels (SetDataNoiseWeights), or by the configured output weights where the
//          stage's experiments set any.
// Default: noise for a stage comparing two or more outputs, given for one (whose estimate
// does not depend on a channel weight).
#pragma once

#include "engine/run/run_config.h"
#include "engine/solve/output_error_problem.h"

namespace vesselid {

// The outputs the stage compares: its `outputs:`, else every output its experiments map.
int ComparedOutputCount(const RunConfig& config, const StageConfig& stage);

bool UsesNoiseWeights(const RunConfig& config, const StageConfig& stage);

// The options the stage's experiments are prepared with (length normalisation as above).
ExperimentOptions StageExperimentOptions(const RunConfig& config, const StageConfig& stage);

// The first solve's weights on the stage's problem: under noise weights each channel 1/sigma
// of the data's own noise level, unless the stage's experiments configure output weights;
// otherwise the configured ones, unchanged. Continuation phases keep the configured ones
// (with the data's they were slower from far starts, docs/benchmarks.md).
void SetFirstSolveWeights(const RunConfig& config, const StageConfig& stage,
                          OutputErrorProblem* problem);

}  // namespace vesselid

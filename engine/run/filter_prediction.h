// A filter-error stage's held-out runs predicted through its filter (`noise:` stages): beside
// the free run from the measured start (what the model does alone, held_out.h), each output
// k samples ahead of the filtered state (what it does with the measurements, as an observer or
// a model-predictive autopilot uses it; k = noise.prediction_steps) and one step ahead (the
// innovations). The held-out run starts from its measured start with the start's variance;
// nothing is fitted on it: the ship's and the disturbance's parameters are the stage's.
#pragma once

#include <string>
#include <vector>

#include "engine/model/model_handle.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/run/trajectory_cache.h"

namespace vesselid {

// The disturbance a stage's noise estimates describe ("sigma.ar1.psi", "q.process.eta2", ...
// as filter-error stages name them): the spec that builds them again (method filter_error),
// or method output_error when there are none.
DisturbanceSpec DisturbanceFromEstimates(const std::vector<Estimate>& estimates);

// Appends to result->summary.notes one line per held-out run and output: the fit (%) of the
// k-step and one-step predictions through the filter, beside the free run's. Nothing when the
// stage has no noise estimates or no held-out runs; a note when the filter diverges.
void PredictHeldOutThroughFilter(const RunConfig& config, const StageConfig& stage,
                                 const ModelHandle& model, const std::vector<double>& values,
                                 TrajectoryCache* cache, StageResult* result);

}  // namespace vesselid

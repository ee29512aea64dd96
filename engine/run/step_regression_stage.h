// A step-regression stage of a staged run (seed 004's identification): regression records
// from the stage's step-response experiments, RunStepRegression, and a StageResult like any
// stage's: every parameter of the model's damping-inertia form estimated (no standard errors:
// the lasso has none), the other parameters held, the regression fit of each term as its
// "fit", the samples and lasso paths attached for the results writer.
#pragma once

#include <string>
#include <vector>

#include "engine/model/model_handle.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/parameter.h"

namespace vesselid {

bool RunStepRegressionStage(const RunConfig& config, const StageConfig& stage,
                            const ModelHandle& model, const std::vector<ParameterSpec>& specs,
                            TrajectoryCache* cache, StageResult* result, std::string* error);

}  // namespace vesselid

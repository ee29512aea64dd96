// A least-squares stage of a staged run: regression records from the stage's experiments,
// RunLeastSquares, and a StageResult like an output-error stage's (estimates with standard
// errors, correlations, the equation-error fit of each regressed state as its "fit").
#pragma once

#include <string>
#include <vector>

#include "engine/model/model_handle.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/parameter.h"

namespace vesselid {

bool RunLeastSquaresStage(const RunConfig& config, const StageConfig& stage,
                          const ModelHandle& model, const std::vector<ParameterSpec>& specs,
                          TrajectoryCache* cache, StageResult* result, std::string* error);

}  // namespace vesselid

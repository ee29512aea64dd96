// An output-error stage of a staged run: its continuation phases (continuation.h), the
// problem of its experiments with the resolved parameters, RunStage (global start, local
// refinements, uncertainty), and a StageResult whose reported starts are the configured ones.
#pragma once

#include <string>
#include <vector>

#include "engine/model/model_handle.h"
#include "engine/run/records.h"
#include "engine/run/run_config.h"
#include "engine/run/run_result.h"
#include "engine/solve/parameter.h"
#include "engine/solve/progress.h"

namespace vesselid {

// `resolved` holds the stage's parameters as ResolveParameters made them and leaves with the
// starts the last continuation phase handed on. `progress` (may be empty) hears every solve.
bool RunOutputErrorStage(const RunConfig& config, const StageConfig& stage,
                         const ModelHandle& model, std::vector<ParameterSpec>* resolved,
                         TrajectoryCache* cache, const ProgressCallback& progress,
                         StageResult* result, std::string* error);

}  // namespace vesselid

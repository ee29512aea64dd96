// `vesselid design <config> --from <run-out>` (and vesselid.design in Python): the next
// experiment planned from a finished run. The run's model, estimate and covariance
// (output/identified_model.h) give today's information I_0 = C^+ over the parameters the run estimated
// (a parameter it could not determine contributes none); the config's `design:` section
// (design_config.h) says what may be planned. The result is written by design_report.h.
#pragma once

#include <string>

#include "engine/config/model_registry.h"
#include "engine/design/design_options.h"
#include "engine/design/design_result.h"

namespace vesselid {

// False with a message naming the file and key.
bool PlanNextExperiment(const ModelRegistry& registry, const DesignOptions& options,
                        const std::string& run_dir, DesignResult* result, std::string* error);

}  // namespace vesselid

// Reads a reference model (run/reference_model.h) from a run's output folder: its results.json
// as `vesselid export` reads it. The shipped registry (problems/registry.h) reads references
// with it.
#pragma once

#include <string>

#include "engine/config/model_registry.h"
#include "engine/model/model_handle.h"
#include "engine/run/reference_model.h"

namespace vesselid {

// Reads the run in `folder` and takes its values for the parameters of `info` (the run's own
// model, of family `family`): the reference must be of the same family and model, with every
// parameter. False with a message naming the file and what differs.
bool ReadReferenceModel(const std::string& folder, const ModelRegistry& registry,
                        const std::string& family, const ModelInfo& info,
                        ReferenceModel* reference, std::string* error);

}  // namespace vesselid

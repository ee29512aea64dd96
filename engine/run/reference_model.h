// A reference model for the final validation (`final_validation: {reference: <folder>}`): the
// identified model of another run (its results.json, as `vesselid export` reads it), flown on
// the same held-out runs from their measured starts as the final values, so that a model
// identified from fewer or other runs is held against one the user already trusts.
#pragma once

#include <string>
#include <vector>

#include "engine/config/model_registry.h"
#include "engine/model/model_handle.h"

namespace vesselid {

struct ReferenceModel {
  std::string folder;         // the run's output folder, as resolved
  std::vector<double> values;  // in `info`'s parameter order
};

// Reads the run in `folder` and takes its values for the parameters of `info` (the run's own
// model, of family `family`): the reference must be of the same family and model, with every
// parameter. False with a message naming the file and what differs.
bool ReadReferenceModel(const std::string& folder, const ModelRegistry& registry,
                        const std::string& family, const ModelInfo& info,
                        ReferenceModel* reference, std::string* error);

}  // namespace vesselid

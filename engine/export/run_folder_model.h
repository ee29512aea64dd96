// The identified model of a finished run read from its output folder (its results.json,
// read once by output/run_document.h), or of a family and options alone.
#pragma once

#include <memory>
#include <string>

#include "engine/config/model_registry.h"
#include "engine/output/identified_model.h"
#include "engine/output/run_document.h"

namespace vesselid {

// The model of `family` with `options` (its variables, units, default parameter values, no
// standard errors, no covariance, no ensemble) and its handle (model->handle); null with a
// message when it cannot be made.
std::shared_ptr<const ModelHandle> MakeIdentifiedModel(const ModelRegistry& registry,
                                                       const std::string& family,
                                                       const ModelOptions& options,
                                                       IdentifiedModel* model, std::string* error);

// The model of the run whose outputs are in `out_folder`, with `members` ensemble members
// drawn with `seed`. False with a message naming the file and key. `document` (may be null)
// gets what the run's results.json says.
bool ReadIdentifiedModel(const std::string& out_folder, const ModelRegistry& registry,
                         int members, unsigned seed, IdentifiedModel* model, std::string* error,
                         RunDocument* document = nullptr);

}  // namespace vesselid

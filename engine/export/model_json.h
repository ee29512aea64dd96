// model.json: an identified model as `vesselid export --format json` writes it (and the FMU's
// resources/model.json), read back by the FMU's runtime and by tools. Its handle is not
// written: a reader makes the model again from family and options.
#pragma once

#include <string>

#include "engine/output/identified_model.h"
#include "nlohmann/json.hpp"

namespace vesselid {

nlohmann::json IdentifiedModelToJson(const IdentifiedModel& model);
bool IdentifiedModelFromJson(const nlohmann::json& j, IdentifiedModel* model, std::string* error);

}  // namespace vesselid

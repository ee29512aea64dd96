// A stage's whole result as data (checkpoints): every member of StageResult and of what it
// holds, as a JSON tree whose numbers are the doubles themselves (NaN and infinities
// included), so that CBOR (json::to_cbor) stores and restores them bit for bit.
#pragma once

#include <string>

#include "engine/run/run_result.h"
#include "nlohmann/json.hpp"

namespace vesselid {

nlohmann::json StageResultToArchive(const StageResult& stage);

// False with a message when `archive` is not a stage result of this version.
bool StageResultFromArchive(const nlohmann::json& archive, StageResult* stage, std::string* error);

}  // namespace vesselid

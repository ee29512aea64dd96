// RunStudy (study.h) with the study document as JSON, for the program's own use of it (its
// notes reach stderr).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/run/run_config.h"
#include "engine/study/study_options.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// On rank 0, `result` holds {config, processes, threads, <part>: {...}} and `text` the
// report; other ranks get null and an empty text.
bool RunStudy(const RunConfig& config, const StudyConfig& study,
              const std::vector<std::string>& only, nlohmann::json* result, std::string* text,
              std::string* error,
              const std::function<void(const std::string&)>& progress = nullptr);

}  // namespace vesselid

// `vesselid study`: the parts of a config's `study` section run one after another, each a
// set of independent cases spread over threads and MPI ranks (study_runner.h), merged on
// rank 0 into one JSON document and a text report.
#pragma once

#include <string>
#include <vector>

#include "engine/run/run_config.h"
#include "engine/study/study_options.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// Names of the parts, in the order they run.
const std::vector<std::string>& StudyPartNames();

// Runs the configured parts (`only` non-empty: just those, each must be configured). On rank
// 0, `result` holds {config, processes, threads, <part>: {...}} and `text` the report; other
// ranks get null and an empty text. `progress` gets one line per finished case.
bool RunStudy(const RunConfig& config, const StudyConfig& study,
              const std::vector<std::string>& only,
              nlohmann::json* result, std::string* text, std::string* error,
              const std::function<void(const std::string&)>& progress = nullptr);

}  // namespace vesselid

// `vesselid study`: the parts of a config's `study` section run one after another, each a
// set of independent cases spread over threads and MPI ranks (study_runner.h), merged on
// rank 0 into one JSON document and a text report.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/run/run_config.h"
#include "engine/study/study_options.h"

namespace vesselid {

// Names of the parts, in the order they run.
const std::vector<std::string>& StudyPartNames();

// Runs the configured parts (`only` non-empty: just those, each must be configured). On rank
// 0, `json` holds study.json's text ({config, processes, threads, <part>: {...}}, as
// `vesselid study` writes it) and `text` the report; other ranks get empty strings.
// `progress` gets one line per finished case. (study_json.h: the document as JSON.)
bool RunStudy(const RunConfig& config, const StudyConfig& study,
              const std::vector<std::string>& only, std::string* json, std::string* text,
              std::string* error,
              const std::function<void(const std::string&)>& progress = nullptr);

}  // namespace vesselid

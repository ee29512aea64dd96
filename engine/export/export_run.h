// `vesselid export` and `vesselid predict` on a finished run's folder, for the command line
// and the Python package alike: the model read from results.json (exported_model.h), written
// as model.json or an FMU, or its standard manoeuvres predicted (manoeuvres.h); the files
// published as one set in their folder (output_staging.h).
#pragma once

#include <string>

#include "engine/config/model_registry.h"
#include "engine/export/manoeuvres.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// Writes the run's model as `format` ("json": <model>.json, "fmu": <model>.fmu, with the FMU
// runtime `runtime`; "c": <model>.h, <model>.c and <model>_example.c, c_model.h) into
// `out_dir` (empty: <run_dir>/export); `path` gets the file written (the header for "c").
bool ExportRun(const ModelRegistry& registry, const std::string& run_dir, const std::string& format,
               std::string out_dir, int members, unsigned seed, const std::string& runtime,
               std::string* path, std::string* error);

// The standard manoeuvres the run's model predicts (the model's own length where `conditions`
// has none), and its held-out zigzags measured against predicted (held_out_zigzags.h):
// `predictions` as predictions.json, `text` as predictions.txt; both written into `out_dir`
// (<run_dir>/predict when empty) unless `write` is false.
bool PredictRun(const ModelRegistry& registry, const std::string& run_dir,
                ManoeuvreConditions conditions, int members, unsigned seed, bool write,
                std::string out_dir, nlohmann::json* predictions, std::string* text,
                std::string* error);

}  // namespace vesselid

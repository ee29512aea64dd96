// `vesselid export` and `vesselid predict`, for the command line and the Python package
// alike: a run's identified model (in memory, or read from its folder's results.json by
// run_folder_model.h) written as model.json, C or an FMU, or its standard manoeuvres
// predicted (manoeuvres.h); the files published as one set in their folder (published_set.h).
#pragma once

#include <string>
#include <vector>

#include "engine/config/model_registry.h"
#include "engine/export/manoeuvres.h"
#include "engine/output/held_out_zigzags.h"
#include "engine/output/identified_model.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// Writes `model` (its handle set; its ensemble drawn) as `format` into `out_dir`, as below.
bool ExportModel(const IdentifiedModel& model, const std::string& format,
                 const std::string& out_dir, const std::string& runtime, std::string* path,
                 std::string* error);

// Writes the run's model as `format` ("json": <model>.json, "fmu": <model>.fmu, with the FMU
// runtime `runtime`; "c": <model>.h, <model>.c and <model>_example.c, c_model.h) into
// `out_dir` (empty: <run_dir>/export); `path` gets the file written (the header for "c").
bool ExportRun(const ModelRegistry& registry, const std::string& run_dir, const std::string& format,
               std::string out_dir, int members, unsigned seed, const std::string& runtime,
               std::string* path, std::string* error);

// Members (>= 2) and a length and speed where given within a ship's; false with a message.
bool CheckPredictionArguments(const ManoeuvreConditions& conditions, int members,
                              std::string* error);

// The standard manoeuvres `model` (its handle set, its ensemble drawn) predicts, its run's
// `zigzags` held out measured against predicted, as below; written into `out_dir` when `write`.
bool PredictModel(const IdentifiedModel& model, const std::vector<ZigzagEntry>& zigzags,
                  ManoeuvreConditions conditions, bool write, const std::string& out_dir,
                  nlohmann::json* predictions, std::string* text, std::string* error);

// The standard manoeuvres the run's model predicts (the model's own length where `conditions`
// has none), and its held-out zigzags measured against predicted (held_out_zigzags.h):
// `predictions` as predictions.json, `text` as predictions.txt; both written into `out_dir`
// (<run_dir>/predict when empty) unless `write` is false.
bool PredictRun(const ModelRegistry& registry, const std::string& run_dir,
                ManoeuvreConditions conditions, int members, unsigned seed, bool write,
                std::string out_dir, nlohmann::json* predictions, std::string* text,
                std::string* error);

}  // namespace vesselid

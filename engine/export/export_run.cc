#include "engine/export/export_run.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "engine/base/atomic_file.h"
#include "engine/base/file_name.h"
#include "engine/export/c_model.h"
#include "engine/export/model_json.h"
#include "engine/export/run_folder_model.h"
#include "engine/export/fmu_package.h"
#include "engine/output/held_out_zigzags.h"
#include "engine/output/output_folder.h"
#include "engine/output/published_set.h"

namespace vesselid {

namespace fs = std::filesystem;

bool ExportModel(const IdentifiedModel& model, const std::string& format,
                 const std::string& out_dir, const std::string& runtime, std::string* path,
                 std::string* error) {
  if (format != "json" && format != "fmu" && format != "c") {
    *error = "unknown export format '" + format + "' (c, fmu, json)";
    return false;
  }
  if (model.handle == nullptr) {
    *error = model.results + ": the model has no handle to export (made from model.json?)";
    return false;
  }
  std::vector<std::pair<std::string, std::function<bool(const std::string&, std::string*)>>> files;
  std::vector<CModelFile> sources;
  if (format == "c") {
    if (!MakeCModel(model, *model.handle, &sources, error)) return false;
    // The example last: the set is published when its last file is in place.
    for (const CModelFile& source : sources) {
      files.push_back({source.name, [&source](const std::string& file, std::string* message) {
                         return WriteFileAtomically(file, source.text, message);
                       }});
    }
  } else {
    files.push_back({FileNameOf(model.model) + "." + format,
                     [&](const std::string& file, std::string* message) {
                       return format == "fmu"
                                  ? WriteFmu(model, runtime, file, message)
                                  : WriteFileAtomically(
                                        file, IdentifiedModelToJson(model).dump(2) + "\n", message);
                     }});
  }
  if (!PublishSet(out_dir, "export." + format, model.results, files, error)) return false;
  // The file to open: the model.json, the FMU, or the C header.
  *path = (fs::path(out_dir) / files.front().first).string();
  return true;
}

bool ExportRun(const ModelRegistry& registry, const std::string& run_dir, const std::string& format,
               std::string out_dir, int members, unsigned seed, const std::string& runtime,
               std::string* path, std::string* error) {
  if (format != "json" && format != "fmu" && format != "c") {
    *error = "unknown export format '" + format + "' (c, fmu, json)";
    return false;
  }
  if (members < 0) {
    *error = "--members must be >= 0";
    return false;
  }
  if (out_dir.empty() && !DefaultOutFolder(run_dir, "export", &out_dir, error)) return false;
  IdentifiedModel model;
  return ReadIdentifiedModel(run_dir, registry, members, seed, &model, error) &&
         ExportModel(model, format, out_dir, runtime, path, error);
}

bool CheckPredictionArguments(const ManoeuvreConditions& conditions, int members,
                              std::string* error) {
  if (members < 2) {
    *error = "--members must be >= 2 (the ensemble interval)";
    return false;
  }
  // A ship's length and approach speed, where given: 1 cm to 1 km, 1 mm/s to 50 m/s (100 kn).
  if (!std::isnan(conditions.length) && !(conditions.length >= 0.01 && conditions.length <= 1000.0)) {
    *error = "--length " + std::to_string(conditions.length) + ": a ship's length in m, 0.01 to 1000";
    return false;
  }
  if (!std::isnan(conditions.speed) && !(conditions.speed >= 0.001 && conditions.speed <= 50.0)) {
    *error = "--speed " + std::to_string(conditions.speed) +
             ": an approach speed in m/s, 0.001 to 50";
    return false;
  }
  return true;
}

bool PredictModel(const IdentifiedModel& model, const std::vector<ZigzagEntry>& zigzags,
                  ManoeuvreConditions conditions, bool write, const std::string& out_dir,
                  nlohmann::json* predictions, std::string* text, std::string* error) {
  // The model's own length (an n1-form Nomoto model on L) unless the conditions give one.
  const auto length = model.options.find("length");
  if (!std::isfinite(conditions.length) && length != model.options.end()) {
    conditions.length = std::strtod(length->second.c_str(), nullptr);
  }
  if (model.handle == nullptr) {
    *error = model.results + ": the model has no handle to fly (made from model.json?)";
    return false;
  }
  ManoeuvrePredictions figures;
  if (!PredictManoeuvres(model, *model.handle, conditions, &figures, error)) return false;
  *text = ManoeuvresText(figures);
  *predictions = ManoeuvresToJson(figures);
  // The zigzags the run held out, measured against predicted.
  const HeldOutZigzagCheck held_out = CheckHeldOutZigzags(zigzags);
  const std::string held_out_text = HeldOutZigzagsText(held_out);
  if (!held_out_text.empty()) *text += "\n" + held_out_text;
  (*predictions)["held_out_zigzags"] = HeldOutZigzagsToJson(held_out);
  (*predictions)["model"] = model.model;
  (*predictions)["results"] = model.results;
  if (!write) return true;
  const std::string json_text = predictions->dump(2) + "\n";
  auto text_file = [&](const std::string& file, std::string* message) {
    return WriteFileAtomically(file, *text, message);
  };
  auto json_file = [&](const std::string& file, std::string* message) {
    return WriteFileAtomically(file, json_text, message);
  };
  return PublishSet(out_dir, "predict", model.results,
                    {{"predictions.txt", text_file}, {"predictions.json", json_file}}, error);
}

bool PredictRun(const ModelRegistry& registry, const std::string& run_dir,
                ManoeuvreConditions conditions, int members, unsigned seed, bool write,
                std::string out_dir, nlohmann::json* predictions, std::string* text,
                std::string* error) {
  if (!CheckPredictionArguments(conditions, members, error)) return false;
  IdentifiedModel model;
  RunDocument run;
  if (!ReadIdentifiedModel(run_dir, registry, members, seed, &model, error, &run)) return false;
  if (write && out_dir.empty() && !DefaultOutFolder(run_dir, "predict", &out_dir, error)) {
    return false;
  }
  return PredictModel(model, run.zigzags, conditions, write, out_dir, predictions, text, error);
}

}  // namespace vesselid

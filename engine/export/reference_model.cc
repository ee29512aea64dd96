#include "engine/export/reference_model.h"

#include <filesystem>

#include "nlohmann/json.hpp"

#include "engine/export/model_json.h"
#include "engine/export/run_folder_model.h"

namespace vesselid {

bool ReadReferenceModel(const std::string& folder, const ModelRegistry& registry,
                        const std::string& family, const ModelInfo& info,
                        ReferenceModel* reference, std::string* error) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(folder, ec)) {
    *error = folder + ": a file; name the reference run's output folder (the folder that holds "
                      "its results.json)";
    return false;
  }
  IdentifiedModel model;
  RunDocument run;
  if (!ReadIdentifiedModel(folder, registry, 0, 0, &model, error, &run)) return false;
  const std::string file = (std::filesystem::path(folder) / "results.json").string();
  if (model.family != family || model.model != info.name) {
    *error = file + ": the reference is a " + model.family + " model (" + model.model +
             "), this run's is " + family + " (" + info.name + ")";
    return false;
  }
  const std::filesystem::path resolved = std::filesystem::weakly_canonical(folder, ec);
  reference->folder = ec ? folder : resolved.string();
  reference->values.clear();
  // Every parameter as the reference run reported it (the exported model would fill one it
  // lacks with the model's default, which is not the reference's).
  for (const std::string& name : info.parameters) {
    bool reported = false;
    for (const RunDocument::Parameter& p : run.parameters) reported = reported || p.name == name;
    size_t k = 0;
    while (k < model.parameters.size() && model.parameters[k].name != name) ++k;
    if (!reported || k == model.parameters.size()) {
      *error = file + ": parameters: the reference reports no '" + name + "'";
      return false;
    }
    reference->values.push_back(model.values[k]);
  }
  return true;
}

}  // namespace vesselid

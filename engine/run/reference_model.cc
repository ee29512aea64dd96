#include "engine/run/reference_model.h"

#include <filesystem>

#include "engine/export/exported_model.h"

namespace vesselid {

bool ReadReferenceModel(const std::string& folder, const ModelRegistry& registry,
                        const std::string& family, const ModelInfo& info,
                        ReferenceModel* reference, std::string* error) {
  ExportedModel model;
  if (!ReadExportedModel(folder, registry, 0, 0, &model, error)) return false;
  const std::string file = (std::filesystem::path(folder) / "results.json").string();
  if (model.family != family || model.model != info.name) {
    *error = file + ": the reference is a " + model.family + " model (" + model.model +
             "), this run's is " + family + " (" + info.name + ")";
    return false;
  }
  reference->folder = folder;
  reference->values.clear();
  for (const std::string& name : info.parameters) {
    size_t k = 0;
    while (k < model.parameters.size() && model.parameters[k].name != name) ++k;
    if (k == model.parameters.size()) {
      *error = file + ": the reference has no parameter '" + name + "'";
      return false;
    }
    reference->values.push_back(model.values[k]);
  }
  return true;
}

}  // namespace vesselid

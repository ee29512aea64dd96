#include "engine/export/run_folder_model.h"

namespace vesselid {

std::shared_ptr<const ModelHandle> MakeIdentifiedModel(const ModelRegistry& registry,
                                                       const std::string& family,
                                                       const ModelOptions& options,
                                                       IdentifiedModel* model, std::string* error) {
  std::shared_ptr<const ModelHandle> handle = registry.MakeModel(family, options, error);
  if (handle != nullptr) DescribeModel(handle, family, options, model);
  return handle;
}

bool ReadIdentifiedModel(const std::string& out_folder, const ModelRegistry& registry,
                         int members, unsigned seed, IdentifiedModel* model, std::string* error,
                         RunDocument* document) {
  RunDocument read;
  if (!ReadRunDocument(out_folder, &read, error)) return false;
  std::shared_ptr<const ModelHandle> handle = registry.MakeModel(read.family, read.options, error);
  if (handle == nullptr) {
    *error = read.path + ": model: " + *error;
    return false;
  }
  if (!IdentifiedModelOf(read, std::move(handle), members, seed, model, error)) return false;
  if (document != nullptr) *document = std::move(read);
  return true;
}

}  // namespace vesselid

#include "engine/output/published_set.h"

#include <filesystem>
#include <memory>

#include "engine/output/output_folder.h"
#include "engine/output/output_staging.h"

namespace vesselid {

bool PublishSet(const std::string& out_dir, const std::string& set, const std::string& input,
                const std::vector<std::pair<std::string, FileWriter>>& files, std::string* error) {
  PlannedOutputs planned;
  for (const auto& file : files) planned.files.push_back(file.first);
  if (!CheckInputsSurvive(out_dir, planned, {input}, error)) return false;
  const std::unique_ptr<OutputFolder> folder = OutputFolder::Open(out_dir, error);
  if (folder == nullptr) return false;
  const std::unique_ptr<OutputStaging> staging =
      OutputStaging::Begin(out_dir, set, error);
  if (staging == nullptr) return false;
  for (const auto& [name, write] : files) {
    if (!write((std::filesystem::path(staging->folder()) / name).string(), error)) return false;
  }
  return staging->Publish(planned.files.back(), error);
}

}  // namespace vesselid

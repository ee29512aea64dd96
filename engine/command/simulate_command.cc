#include "engine/command/simulate_command.h"

#include <filesystem>
#include <memory>

#include "engine/base/file_name.h"
#include "engine/base/stop_request.h"
#include "engine/output/output_folder.h"
#include "engine/output/output_staging.h"

namespace vesselid {

bool SimulateCommand(const ConfigFile& config, const std::string& config_name,
                     const std::string& out_dir, bool config_is_file,
                     std::vector<std::string>* files, std::string* error) {
  if (!SimulateConfig(config, out_dir, error, /*check_only=*/true)) return false;
  PlannedOutputs planned;
  for (const ExperimentSpec& spec : config.run.experiments) {
    planned.files.push_back(std::filesystem::path(spec.file).filename().string());
  }
  std::vector<std::string> inputs;
  if (config_is_file) inputs.push_back(config_name);
  if (!CheckInputsSurvive(out_dir, planned, inputs, error)) return false;
  const auto folder = OutputFolder::Open(out_dir, error);
  if (folder == nullptr) return false;
  const std::string set =
      "simulate." + FileNameOf(std::filesystem::path(config_name).stem().string());
  const auto staging = OutputStaging::Begin(out_dir, set, error);
  if (staging == nullptr || !SimulateConfig(config, staging->folder(), error)) return false;
  if (StopRequested()) {
    *error = "stopped before the simulated files were published";
    return false;
  }
  if (!planned.files.empty() && !staging->Publish(planned.files.back(), error)) return false;
  *files = planned.files;
  return true;
}

}  // namespace vesselid

#include "engine/command/design_command.h"

#include "engine/design/design_config.h"
#include "engine/design/design_report.h"
#include "engine/design/design_run.h"

namespace vesselid {

bool DesignCommand(const ModelRegistry& registry, const std::string& config,
                   const std::string& text, const std::string& run_dir, int threads, bool write,
                   const std::string& out_dir, DesignResult* result, std::string* error,
                   bool* config_error) {
  DesignOptions options;
  if (config_error != nullptr) *config_error = false;
  if (!LoadDesign(config, &options, error, text)) {
    if (config_error != nullptr) *config_error = true;
    return false;
  }
  if (threads > 0) options.threads = threads;
  return PlanNextExperiment(registry, options, run_dir, result, error) &&
         (!write || WriteDesign(*result, out_dir, error));
}

}  // namespace vesselid

// Fuzz target for LoadConfigFile (engine/config/config.h) with every model family of the vesselid
// binary, study section included: any bytes give either a config that keeps the reader's
// promises (known experiments, valid parameters and study options) or false with a message
// naming the file. Experiment files are only named by a config, not read, so none is needed.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/config/config.h"
#include "engine/config/model_family.h"
#include "engine/study/partition_study.h"
#include "problems/registry.h"
#include "tests/fuzz/fuzz_input_file.h"

// Undefined behaviour is a finding, not a warning: stop at the first report so that
// libFuzzer keeps the input.
extern "C" const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }

namespace vesselid {
namespace {

void CheckStudy(const RunConfig& config, const StudyConfig& study) {
  FUZZ_CHECK(study.execution.threads >= 0);
  if (study.profile) {
    FUZZ_CHECK(study.profile->points >= 3 && study.profile->points % 2 == 1);
    FUZZ_CHECK(study.profile->span > 0.0);
    FUZZ_CHECK(study.profile->confidence > 0.0 && study.profile->confidence < 1.0);
  }
  if (study.monte_carlo) FUZZ_CHECK(study.monte_carlo->runs >= 1);
  if (study.starts) FUZZ_CHECK(study.starts->runs >= 1 && study.starts->tolerance > 0.0);
  if (study.partitions) {
    std::string error;
    FUZZ_CHECK(study.partitions->IsValid(&error));
    FUZZ_CHECK(PartitionStudyStage(config, study.partitions->stage) != nullptr);
  }
}

void CheckConfig(const ConfigFile& file) {
  const RunConfig& config = file.run;
  FUZZ_CHECK(config.model != nullptr && file.family != nullptr);
  FUZZ_CHECK(file.family->name == config.family);
  for (const ExperimentSpec& e : config.experiments) {
    FUZZ_CHECK(config.FindExperiment(e.name) == &e);
    FUZZ_CHECK(!(e.t_begin >= e.t_end));
  }
  FUZZ_CHECK(!config.stages.empty());
  for (const StageConfig& stage : config.stages) {
    FUZZ_CHECK(!stage.experiments.empty());
    for (const std::string& name : stage.experiments) {
      FUZZ_CHECK(config.FindExperiment(name) != nullptr);
    }
    for (const std::string& name : stage.validation) {
      FUZZ_CHECK(config.FindExperiment(name) != nullptr);
    }
    for (const ParameterSpec& parameter : stage.parameters) {
      std::string error;
      FUZZ_CHECK(parameter.IsValid(config.path, &error));
    }
  }
  if (config.has_final_validation) {
    for (const std::string& name : config.final_validation.experiments) {
      FUZZ_CHECK(config.FindExperiment(name) != nullptr);
    }
  }
  CheckStudy(config, file.study);
}

}  // namespace
}  // namespace vesselid

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const vesselid::ModelRegistry registry = vesselid::DefaultRegistry();
  static vesselid::fuzz::FuzzInputFile file("config.yaml");
  const std::string& path = file.Write(data, size);
  vesselid::ConfigFile config;
  std::string error;
  if (!vesselid::LoadConfigFile(path, "", registry, &config, &error)) {
    FUZZ_CHECK(error.compare(0, path.size() + 1, path + ":") == 0);
    return 0;
  }
  vesselid::CheckConfig(config);
  return 0;
}

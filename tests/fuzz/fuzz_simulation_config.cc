// Fuzz target for the model families' `simulation` readers (SimulateConfig with check_only,
// engine/config/config.h): any bytes that load as a config give either a simulation section
// every family accepts within the config's limits, or false with a message naming the file.
// Nothing is simulated or written.
#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/config/config.h"
#include "problems/registry.h"
#include "tests/fuzz/fuzz_input_file.h"

// Undefined behaviour is a finding, not a warning: stop at the first report so that
// libFuzzer keeps the input.
extern "C" const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const vesselid::ModelRegistry registry = vesselid::DefaultRegistry();
  static vesselid::fuzz::FuzzInputFile file("config.yaml");
  const std::string& path = file.Write(data, size);
  vesselid::ConfigFile config;
  std::string error;
  if (!vesselid::LoadConfigFile(path, "", registry, &config, &error)) return 0;
  if (!vesselid::SimulateConfig(config, "", &error, /*check_only=*/true)) {
    FUZZ_CHECK(error.compare(0, path.size() + 1, path + ":") == 0);
  }
  return 0;
}

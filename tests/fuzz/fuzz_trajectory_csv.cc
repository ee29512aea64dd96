// Fuzz target for ReadTrajectoryCsv (engine/data/trajectory.h): any bytes give either a trajectory
// that keeps the reader's promises (strictly increasing finite time, one finite-or-NaN value
// per row and channel) or false with a "file:line: ..." message.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include "engine/data/trajectory.h"
#include "tests/fuzz/fuzz_input_file.h"

// Undefined behaviour is a finding, not a warning: stop at the first report so that
// libFuzzer keeps the input.
extern "C" const char* __ubsan_default_options() { return "halt_on_error=1:print_stacktrace=1"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static vesselid::fuzz::FuzzInputFile file("input.csv");
  const std::string& path = file.Write(data, size);
  vesselid::Trajectory trajectory;
  std::string error;
  if (!vesselid::ReadTrajectoryCsv(path, &trajectory, &error)) {
    FUZZ_CHECK(error.compare(0, path.size() + 1, path + ":") == 0);
    return 0;
  }
  FUZZ_CHECK(trajectory.source == path);
  FUZZ_CHECK(trajectory.t.size() >= 2);
  for (size_t k = 0; k < trajectory.t.size(); ++k) {
    FUZZ_CHECK(std::isfinite(trajectory.t[k]));
    FUZZ_CHECK(k == 0 || trajectory.t[k] > trajectory.t[k - 1]);
  }
  FUZZ_CHECK(trajectory.columns.size() == trajectory.names.size());
  std::set<std::string> names;  // not Find() per name: quadratic in a wide header
  for (size_t c = 0; c < trajectory.columns.size(); ++c) {
    FUZZ_CHECK(!trajectory.names[c].empty() && trajectory.names[c] != "t");
    FUZZ_CHECK(names.insert(trajectory.names[c]).second);
    FUZZ_CHECK(trajectory.columns[c].size() == trajectory.t.size());
    for (double v : trajectory.columns[c]) FUZZ_CHECK(std::isnan(v) || std::isfinite(v));
    const vesselid::Channel channel = vesselid::ExtractChannel(trajectory, static_cast<int>(c));
    FUZZ_CHECK(channel.t.size() == channel.value.size());
  }
  return 0;
}

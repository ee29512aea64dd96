// Limits on what one config may ask of the machine, checked before the work starts so that a
// mistyped value ("max_step: 1e-7", "runs: 1e9") or a hostile input file is refused with the
// number and the key that caused it, not found by the kernel's out-of-memory killer. The
// defaults admit a day of 100 Hz logging; the config's `limits` section raises them.
#pragma once

#include <cstdint>

namespace vesselid {

struct WorkLimits {
  std::uint64_t file_bytes = std::uint64_t{1} << 30;  // one data file (limits.file_mb)
  std::uint64_t data_values = 50'000'000;             // rows x columns of one data file
  // Integration steps of one record's simulation, all the pieces it is cut into together
  // (checked before the run; BuildExperiment checks each piece again), or of a simulated run.
  std::uint64_t integration_steps = 20'000'000;
  std::uint64_t study_cases = 100'000;     // solves of a study part (runs x stages, points)
  std::uint64_t evaluations = 10'000'000;  // global-start evaluations of one stage
  std::uint64_t files = 10'000;            // files matched by the `files` patterns together
  std::uint64_t experiments = 10'000;      // experiments of the config, `files` expanded
  // Data files may lie outside the data folder (--data, else the config's folder): an
  // absolute `file`, a `../` path or pattern (limits.outside_data).
  bool outside_data = false;
  // The run's memory budget (limits.memory_mb; memory_budget.h), 0: half the machine's memory.
  std::uint64_t memory_bytes = 0;
};

// A config file is read whole by the YAML parser: no limit key, it is never large.
constexpr std::uint64_t kMaxConfigBytes = std::uint64_t{16} << 20;

}  // namespace vesselid

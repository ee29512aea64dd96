// Set-up shared by the benchmarks: a shipped config loaded against a temporary data folder
// and its family's campaign simulated into it.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>

#include "engine/config/config.h"
#include "problems/registry.h"

namespace vesselid::benchmark {

using Clock = std::chrono::steady_clock;

inline double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// Mean time of `f` over enough repetitions to take at least `min_seconds`.
template <class F>
double MeanTime(F&& f, double min_seconds) {
  int reps = 0;
  const auto start = Clock::now();
  do {
    f();
    ++reps;
  } while (Seconds(start) < min_seconds);
  return Seconds(start) / reps;
}

inline std::filesystem::path DataFolder(const std::string& folder) {
  return std::filesystem::temp_directory_path() / folder;
}

// Loads `path` with experiments resolved in /tmp/<folder>, simulates the campaign there and
// reports the simulation time. The registry must outlive the config.
inline bool LoadAndSimulate(const std::string& path, const std::string& folder,
                            const ModelRegistry& registry, RunConfig* config,
                            double* simulation_seconds, std::string* error) {
  const std::filesystem::path data = DataFolder(folder);
  std::filesystem::create_directories(data);
  ConfigFile file;
  if (!LoadConfigFile(path, data.string(), registry, &file, error)) return false;
  const auto start = Clock::now();
  if (!SimulateConfig(file, data.string(), error)) return false;
  *simulation_seconds = Seconds(start);
  *config = std::move(file.run);
  return true;
}

}  // namespace vesselid::benchmark

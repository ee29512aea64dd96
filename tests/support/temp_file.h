// A small text file in the system's temporary folder, for reader tests.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace vesselid::testing {

// Writes `text` to <temp>/<name> and returns its path.
inline std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace vesselid::testing

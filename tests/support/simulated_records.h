// The records `vesselid simulate configs/<name>.yaml` writes, simulated once and shared by
// every test process that reads them. CTest runs each test case in a process of its own, so a
// suite's fixture cannot hold them: the Eriksen craft's records alone take 1.5 s to simulate,
// and four cases read them. Tests only read the folder (a run's --data); one that writes
// beside its records simulates its own.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <system_error>

namespace vesselid::testing {

// <build>/tests/simulated/<name>-<key>: the key changes with the config's text and with the
// program (its size and time of writing), so that a rebuilt engine or an edited config
// simulates again. The folder appears whole or not at all: it is simulated into a folder of
// its own and renamed into place; a process that loses the race to another uses the winner's.
// An empty path when the simulation fails.
inline std::filesystem::path SimulatedRecords(const std::string& name) {
  namespace fs = std::filesystem;
  const std::string config = std::string(VESSELID_SOURCE_DIR) + "/configs/" + name + ".yaml";
  const fs::path binary = VESSELID_BINARY;
  std::ifstream in(config);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::error_code ec;
  const std::string program = std::to_string(fs::file_size(binary, ec)) + "/" +
                              std::to_string(fs::last_write_time(binary, ec)
                                                 .time_since_epoch()
                                                 .count());
  const size_t key = std::hash<std::string>{}(text + "\n" + program);
  const fs::path folder = binary.parent_path() / "tests" / "simulated" /
                          (name + "-" + std::to_string(key));
  if (fs::is_directory(folder, ec)) return folder;
  const fs::path scratch = folder.string() + ".part" + std::to_string(::getpid());
  fs::remove_all(scratch, ec);
  fs::create_directories(scratch.parent_path(), ec);
  const std::string simulate = binary.string() + " simulate " + config + " --out " +
                               scratch.string() + " > /dev/null";
  if (std::system(simulate.c_str()) != 0) {
    fs::remove_all(scratch, ec);
    return {};
  }
  fs::rename(scratch, folder, ec);  // fails when another process's folder is there first
  if (ec) fs::remove_all(scratch, ec);
  return fs::is_directory(folder, ec) ? folder : fs::path();
}

}  // namespace vesselid::testing

// A folder of configs and simulated data that `vesselid study` runs on, as a user would run it
// (one folder per test process: CTest runs tests in parallel processes).
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/study_json.h"
#include "yaml-cpp/yaml.h"

namespace vesselid::testing {

class StudyFolder {
 public:
  explicit StudyFolder(const std::string& name)
      : dir_(std::filesystem::temp_directory_path() /
             (name + "_" + std::to_string(getpid()))) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~StudyFolder() { std::filesystem::remove_all(dir_); }

  const std::filesystem::path& dir() const { return dir_; }

  void Write(const std::string& name, const YAML::Node& config) const {
    YAML::Emitter out;
    out << config;
    std::ofstream(dir_ / name) << out.c_str() << "\n";
  }

  // `vesselid simulate <config>` into the folder.
  void Simulate(const std::string& config) const {
    const std::string simulate = std::string(VESSELID_BINARY) + " simulate " +
                                 (dir_ / config).string() + " --out " + dir_.string() +
                                 " > /dev/null";
    ASSERT_EQ(std::system(simulate.c_str()), 0) << simulate;
  }

  // `vesselid study <config> --out <out> <options>` on the folder's data, under `launcher`
  // (e.g. mpirun) if given: its exit status, and its stderr in `messages`.
  int Study(const std::string& config, const std::string& out, std::string* messages,
            const std::string& options = "", const std::string& launcher = "") const {
    return Command("study", config, out, messages, options, launcher);
  }

  // `vesselid run <config> --out <out> <options>` on the folder's data: its exit status, and
  // its stderr in `messages`.
  int Run(const std::string& config, const std::string& out, std::string* messages,
          const std::string& options = "") const {
    return Command("run", config, out, messages, options);
  }

  // study.json of `out` (null if missing or unreadable).
  nlohmann::json Load(const std::string& out) const {
    std::ifstream in(dir_ / out / "study.json");
    EXPECT_TRUE(in.good()) << "no study.json in " << out;
    const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    return j.is_discarded() ? nlohmann::json() : j;
  }

 private:
  int Command(const std::string& verb, const std::string& config, const std::string& out,
              std::string* messages, const std::string& options,
              const std::string& launcher = "") const {
    const std::filesystem::path log = dir_ / (out + ".stderr");
    const std::string command = launcher + std::string(VESSELID_BINARY) + " " + verb + " " +
                                (dir_ / config).string() + " --data " + dir_.string() +
                                " --out " + (dir_ / out).string() + " " + options +
                                " --quiet > /dev/null 2> " + log.string();
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    messages->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return status;
  }

  std::filesystem::path dir_;
};

}  // namespace vesselid::testing

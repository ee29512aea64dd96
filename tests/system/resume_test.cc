// A staged run killed mid-way and resumed with --resume gives the results of a run that was
// never interrupted, and leaves nothing but its checkpoint while it is down. The shipped
// Erunsal hierarchy: seven stages; the kill lands in the sixth (spiral, the longest).
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/study_cli.h"

extern char** environ;

namespace vesselid {
namespace resume_test {

using nlohmann::json;
namespace fs = std::filesystem;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Times differ between two runs of the same work; everything else must not.
std::string WithoutTimes(const std::string& text) {
  static const std::regex seconds(R"([0-9]+\.[0-9]+ s\b)");
  return std::regex_replace(text, seconds, "<t> s");
}

json WithoutTimes(json j) {
  if (j.is_object()) {
    j.erase("time_seconds");
    for (auto& item : j.items()) item.value() = WithoutTimes(item.value());
  } else if (j.is_array()) {
    for (auto& item : j) item = WithoutTimes(item);
  } else if (j.is_string()) {
    j = WithoutTimes(j.get<std::string>());
  }
  return j;
}

// The stages in a checkpoint: the run's at work (`folder` ".vesselid-checkpoint") or the one
// published with its results ("checkpoint").
int FinishedStages(const fs::path& out, const std::string& folder = ".vesselid-checkpoint") {
  if (!fs::exists(out / folder / "manifest.json")) return 0;
  const json manifest = json::parse(ReadFile(out / folder / "manifest.json"), nullptr, false);
  return manifest.is_discarded() ? 0 : static_cast<int>(manifest["stages"].size());
}

TEST(ResumeTest, KilledRunResumesToTheUninterruptedResults) {
  testing::StudyFolder folder("vesselid_resume");
  const std::string source = std::string(VESSELID_SOURCE_DIR) + "/configs/erunsal_hierarchy.yaml";
  fs::copy_file(source, folder.dir() / "hierarchy.yaml");
  folder.Simulate("hierarchy.yaml");
  const fs::path whole = folder.dir() / "whole", killed = folder.dir() / "killed";

  std::string messages;
  ASSERT_EQ(folder.Run("hierarchy.yaml", "whole", &messages), 0) << messages;

  // The same run, killed once five stages are checkpointed, inside the sixth.
  const std::string binary = VESSELID_BINARY, config = (folder.dir() / "hierarchy.yaml").string(),
                    data = folder.dir().string(), out = killed.string();
  std::vector<const char*> argv = {binary.c_str(), "run",        config.c_str(), "--data",
                                   data.c_str(),   "--out",      out.c_str(),    "--quiet",
                                   nullptr};
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, binary.c_str(), nullptr, nullptr,
                        const_cast<char* const*>(argv.data()), environ),
            0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(20);
  while (FinishedStages(killed) < 5 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before it was killed";

  // Down: the checkpoint of the five stages, no results and no half-written file.
  EXPECT_EQ(FinishedStages(killed), 5);
  EXPECT_FALSE(fs::exists(killed / "results.json"));
  EXPECT_FALSE(fs::exists(killed / "report.txt"));
  EXPECT_FALSE(fs::exists(killed / "report.html"));
  for (const auto& entry : fs::recursive_directory_iterator(killed)) {
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
  }

  // Another config (or other data) cannot continue this checkpoint.
  std::ofstream(folder.dir() / "edited.yaml") << ReadFile(folder.dir() / "hierarchy.yaml")
                                              << "\n# edited\n";
  EXPECT_NE(folder.Run("edited.yaml", "killed", &messages, "--resume"), 0);
  EXPECT_NE(messages.find("another config or other data"), std::string::npos) << messages;

  ASSERT_EQ(folder.Run("hierarchy.yaml", "killed", &messages, "--resume"), 0) << messages;
  EXPECT_EQ(WithoutTimes(json::parse(ReadFile(killed / "results.json"))),
            WithoutTimes(json::parse(ReadFile(whole / "results.json"))));
  EXPECT_EQ(WithoutTimes(ReadFile(killed / "report.txt")),
            WithoutTimes(ReadFile(whole / "report.txt")));
  int traces = 0;
  for (const auto& entry : fs::directory_iterator(whole / "traces")) {
    EXPECT_EQ(ReadFile(entry.path()), ReadFile(killed / "traces" / entry.path().filename()))
        << entry.path().filename();
    ++traces;
  }
  EXPECT_GT(traces, 0);
  EXPECT_EQ(FinishedStages(killed, "checkpoint"), 7);
  EXPECT_FALSE(fs::exists(killed / ".vesselid-checkpoint"));

  // A damaged stage file is named, not silently rerun.
  std::ofstream(killed / "checkpoint" / "stage_003.cbor", std::ios::trunc) << "damaged";
  EXPECT_NE(folder.Run("hierarchy.yaml", "killed", &messages, "--resume"), 0);
  EXPECT_NE(messages.find("stage_003.cbor"), std::string::npos) << messages;
}

}  // namespace resume_test
}  // namespace vesselid

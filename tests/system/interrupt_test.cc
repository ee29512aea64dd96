// Ctrl-C (SIGINT) or SIGTERM during `vesselid run`: the run stops at the next solver
// iteration, says in one line where it stopped and the command that goes on, exits 128 + the
// signal, and publishes nothing: the folder's previous results stay whole. `--resume` then
// finishes the run. And a late failure while writing (a folder where report.txt goes) leaves
// the previous results whole too.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <thread>

#include "nlohmann/json.hpp"
#include "tests/support/bad_input_fixture.h"

extern char** environ;

namespace vesselid {
namespace interrupt_test {

namespace fs = std::filesystem;
using testing::BadInput;
using testing::Outcome;

// A quick first stage and a long second one (a multistart of many candidates), so that the
// signal lands while a stage runs.
const std::string kTwoStages = std::string(testing::kGoodConfig) + R"(  - name: search
    global: {points: 4000, short_iterations: 30, candidates: 400, seed: 1}
    parameters:
      T: {lower: 0.1, upper: 50.0}
      K: {lower: -1.0, upper: -0.001}
    free_initial_states: [psi]
)";

class Interrupt : public BadInput {
 protected:
  // Long enough that the multistart takes many seconds.
  double RecordSeconds() const override { return 1200.0; }
  static std::string ReadFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  static int FinishedStages(const fs::path& out) {
    // The checkpoint of the run at work (published as checkpoint/ with its results).
    const fs::path manifest = out / ".vesselid-checkpoint" / "manifest.json";
    if (!fs::exists(manifest)) return 0;
    const auto j = nlohmann::json::parse(ReadFile(manifest), nullptr, false);
    return j.is_discarded() ? 0 : static_cast<int>(j["stages"].size());
  }

  // `vesselid run` into `out`, sent `signal` once its checkpoint holds a stage: the exit
  // status (as waitpid gives it) and stderr.
  Outcome RunAndSignal(const fs::path& out, int signal) {
    const std::string binary = VESSELID_BINARY, config = (dir_ / "config.yaml").string(),
                      out_text = out.string(), log = (dir_ / "stderr.txt").string();
    std::vector<const char*> argv = {binary.c_str(),   "run",     config.c_str(), "--out",
                                     out_text.c_str(), "--quiet", nullptr};
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    EXPECT_EQ(posix_spawn(&pid, binary.c_str(), &actions, nullptr,
                          const_cast<char* const*>(argv.data()), environ),
              0);
    posix_spawn_file_actions_destroy(&actions);
    // This run's working checkpoint holds its first stage.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    while (std::chrono::steady_clock::now() < deadline && FinishedStages(out) < 1) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    EXPECT_EQ(kill(pid, signal), 0);
    const auto sent = std::chrono::steady_clock::now();
    int status = 0;
    waitpid(pid, &status, 0);
    stopped_seconds_ =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
    return Outcome{status, ReadFile(log)};
  }

  double stopped_seconds_ = 0.0;
};

TEST_F(Interrupt, SignalStopsTheRunSaysWhereAndPublishesNothing) {
  for (int signal : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal);
    const fs::path out = dir_ / ("out" + std::to_string(signal));
    // A whole earlier set in the folder (one stage), which the stopped run must leave as is.
    WriteConfig(testing::kGoodConfig);
    ASSERT_EQ(Run("", out).status, 0);
    const std::string earlier_results = ReadFile(out / "results.json");
    const std::string earlier_report = ReadFile(out / "report.txt");
    const std::string earlier_checkpoint = ReadFile(out / "checkpoint" / "manifest.json");
    ASSERT_FALSE(earlier_checkpoint.empty());
    WriteConfig(kTwoStages);

    const Outcome outcome = RunAndSignal(out, signal);
    ASSERT_TRUE(WIFEXITED(outcome.status)) << outcome.output;
    EXPECT_EQ(WEXITSTATUS(outcome.status), 128 + signal) << outcome.output;
    const std::string name = signal == SIGINT ? "SIGINT" : "SIGTERM";
    EXPECT_TRUE(std::regex_search(
        outcome.output,
        std::regex("vesselid: interrupted by " + name +
                   " in stage 'search' \\(2 of 2\\); 1 finished stage\\(s\\) are in its "
                   "checkpoint \\(.*/\\.vesselid-checkpoint\\): `vesselid run .*config.yaml --out .* --resume` goes on from "
                   "stage 'search' \\(no results published")))
        << outcome.output;
    // The multistart's screening stops at the next point and its short solves at their next
    // batch, not after 4000 points and 400 candidates: 0.1 s (the screening alone took 1-3 s
    // to notice the signal before it was checked point by point; 10x that sanitized).
    std::printf("%s: stopped %.2f s after the signal\n", name.c_str(), stopped_seconds_);
    EXPECT_LT(stopped_seconds_, 3.0);
    EXPECT_EQ(ReadFile(out / "results.json"), earlier_results);
    EXPECT_EQ(ReadFile(out / "report.txt"), earlier_report);
    // The earlier set keeps its own checkpoint: none of the stopped run's beside its results.
    EXPECT_EQ(ReadFile(out / "checkpoint" / "manifest.json"), earlier_checkpoint);
    EXPECT_FALSE(fs::exists(out / ".vesselid-staging"));
    EXPECT_EQ(FinishedStages(out), 1);  // the stage cut short is not saved
  }
}

TEST_F(Interrupt, ResumeFinishesAStoppedRun) {
  WriteConfig(kTwoStages);
  const fs::path out = dir_ / "out";
  const Outcome stopped = RunAndSignal(out, SIGINT);
  ASSERT_TRUE(WIFEXITED(stopped.status)) << stopped.output;
  ASSERT_EQ(WEXITSTATUS(stopped.status), 130) << stopped.output;
  EXPECT_FALSE(fs::exists(out / "results.json"));
  const std::string command = std::string(VESSELID_BINARY) + " run " +
                              (dir_ / "config.yaml").string() + " --out " + out.string() +
                              " --resume 2>&1 >/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe) != nullptr) output += buffer;
  ASSERT_EQ(pclose(pipe), 0) << output;
  EXPECT_NE(output.find("resuming after stage 'fit'"), std::string::npos) << output;
  const auto results = nlohmann::json::parse(ReadFile(out / "results.json"));
  EXPECT_EQ(results["stages"].size(), 2u);
  // The checkpoint is published with the results; none is left at work.
  const auto checkpoint = nlohmann::json::parse(ReadFile(out / "checkpoint" / "manifest.json"));
  EXPECT_EQ(checkpoint["stages"].size(), 2u);
  EXPECT_FALSE(fs::exists(out / ".vesselid-checkpoint"));
}

// An obstacle where the outputs go (here a folder of the user's where report.txt goes) is
// found before the stages run; a failure while they are written (a full disk) comes after:
// either way the previous set stays whole, nothing of the new one is published, and the
// message names the obstacle.
TEST_F(Interrupt, LateWriteFailureLeavesThePreviousSet) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(Run("", out).status, 0);
  const std::string earlier_results = ReadFile(out / "results.json");
  std::vector<std::string> earlier_traces;
  for (const auto& entry : fs::directory_iterator(out / "traces")) {
    earlier_traces.push_back(entry.path().filename().string());
  }
  fs::remove(out / "report.txt");
  fs::create_directories(out / "report.txt" / "kept");
  EditConfig("name: run", "name: renamed");
  const Outcome outcome = Run("", out);
  EXPECT_NE(outcome.status, 0);
  EXPECT_NE(outcome.output.find("report.txt/kept: vesselid would replace this"),
            std::string::npos)
      << outcome.output;
  EXPECT_EQ(ReadFile(out / "results.json"), earlier_results);
  std::vector<std::string> traces;
  for (const auto& entry : fs::directory_iterator(out / "traces")) {
    traces.push_back(entry.path().filename().string());
  }
  EXPECT_EQ(traces, earlier_traces);
  EXPECT_TRUE(fs::exists(out / "report.txt" / "kept"));
  EXPECT_FALSE(fs::exists(out / ".vesselid-staging"));
}

}  // namespace interrupt_test
}  // namespace vesselid

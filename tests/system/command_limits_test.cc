// `export`, `predict` and `design` under the guarantees `run` keeps: every figure that sizes
// their memory (ensemble members, planned samples, the results.json read) checked against the
// budget before anything is allocated, with a refusal that names the flag or key and the
// figure; inputs checked (a covariance that is none, a ship of no length, a FIFO for a file);
// and no child process above 1 GiB on the way.
#include <sys/resource.h>
#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <regex>
#include <string>

#include "engine/output/reserved_names.h"
#include "gtest/gtest.h"
#include "nlohmann/json.hpp"
#include "tests/support/run_command.h"

namespace vesselid {
namespace command_limits_test {

namespace fs = std::filesystem;
using nlohmann::json;

using testing::CommandOutcome;

// `vesselid <arguments>`; `timeout`: a command that blocks (a FIFO opened for reading) fails the
// test, not CI.
CommandOutcome Command(const std::string& arguments) {
  return testing::RunCommand("timeout 60 " + std::string(VESSELID_BINARY) + " " + arguments);
}

// A file's bytes ("" when it cannot be read).
std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Largest resident set of any child process so far, MiB.
double ChildPeakMiB() {
  struct rusage usage;
  ::getrusage(RUSAGE_CHILDREN, &usage);
  return usage.ru_maxrss / 1024.0;
}

class CommandLimits : public ::testing::Test {
 protected:
  // One folder per case (ctest runs the cases as processes side by side), with a finished run
  // of the shipped design campaign (1 s).
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("vesselid_command_limits_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    const std::string config = std::string(VESSELID_SOURCE_DIR) + "/configs/design_cargo.yaml";
    ASSERT_EQ(Command("simulate " + config + " --out " + (dir_ / "data").string()).status, 0);
    const CommandOutcome run = Command("run " + config + " --data " + (dir_ / "data").string() +
                                " --out " + (dir_ / "run").string() + " --quiet --no-report");
    ASSERT_EQ(run.status, 0) << run.output;
  }
  void TearDown() override { fs::remove_all(dir_); }
  // A copy of the run's folder whose results.json `edit` changed.
  std::string EditedRun(const std::string& name, const std::function<void(json*)>& edit) {
    const fs::path copy = dir_ / name;
    fs::remove_all(copy);
    fs::create_directories(copy);
    std::ifstream in(dir_ / "run" / "results.json");
    json results = json::parse(in);
    edit(&results);
    std::ofstream(copy / "results.json") << results.dump();
    return copy.string();
  }
  // configs/design_cargo.yaml with the first `from` replaced by `to`, written as `name`.
  std::string EditedDesignConfig(const std::string& from, const std::string& to,
                                 const std::string& name) {
    std::ifstream in(std::string(VESSELID_SOURCE_DIR) + "/configs/design_cargo.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  static void ExpectRefused(const CommandOutcome& outcome, const std::string& pattern) {
    EXPECT_NE(outcome.status, 0) << outcome.output;
    EXPECT_TRUE(std::regex_search(outcome.output, std::regex(pattern)))
        << "expected /" << pattern << "/ in:\n" << outcome.output;
    EXPECT_EQ(outcome.output.find("terminate called"), std::string::npos) << outcome.output;
    EXPECT_LT(ChildPeakMiB(), 1024.0);
  }
  fs::path dir_;
};

TEST_F(CommandLimits, EnsembleMembersBeyondTheBudgetAreRefused) {
  const std::string run = (dir_ / "run").string();
  ExpectRefused(Command("export " + run + " --format json --members 100000000 --out " +
                        (dir_ / "export").string()),
                "--members 100000000: the ensemble's draws need [0-9.]+ [GMT]iB, more than the "
                "memory budget");
  ExpectRefused(Command("predict " + run + " --members 1000000000 --out " +
                        (dir_ / "predict").string()),
                "--members 1000000000: the ensemble's draws need");
  EXPECT_FALSE(fs::exists(dir_ / "export" / "results.json"));
}

TEST_F(CommandLimits, AShipOfNoLengthOrSpeedIsRefused) {
  const std::string run = (dir_ / "run").string();
  ExpectRefused(Command("predict " + run + " --length 0 --speed 0 --out " +
                        (dir_ / "predict_zero").string()),
                "--length 0.0+: a ship's length in m");
  ExpectRefused(Command("predict " + run + " --length 100 --speed -3 --out " +
                        (dir_ / "predict_zero").string()),
                "--speed -3.0+: an approach speed in m/s");
}

// An edited results.json: a correlation of 5 (no covariance has it) or a standard error of
// 1e300 (its variance overflows) draws no ensemble; the parameters are named.
TEST_F(CommandLimits, ACovarianceThatIsNoneIsRefusedNamingTheParameters) {
  const std::string bad_correlation = EditedRun("correlation_5", [](json* r) {
    for (json& stage : (*r)["stages"]) {
      if (stage.contains("correlation") && stage["correlation"]["matrix"].size() > 1) {
        stage["correlation"]["matrix"][0][1] = 5.0;
        stage["correlation"]["matrix"][1][0] = 5.0;
      }
    }
  });
  ExpectRefused(Command("export " + bad_correlation + " --format json"),
                "the correlation of T[123] and T[123] is not a correlation");
  const std::string huge_se = EditedRun("std_error_1e300", [](json* r) {
    for (json& p : (*r)["parameters"]) {
      if (p["name"] == "K") p["std_error"] = 1e300;
    }
  });
  ExpectRefused(Command("predict " + huge_se), "the variance of K is not a finite number");
}

TEST_F(CommandLimits, AFifoForResultsIsRefusedWithoutBlocking) {
  const fs::path folder = dir_ / "fifo";
  fs::create_directories(folder);
  ASSERT_EQ(::mkfifo((folder / "results.json").c_str(), 0644), 0);
  ExpectRefused(Command("export " + folder.string() + " --format json"),
                "results.json: not a regular file");
}

TEST_F(CommandLimits, ResultsLargerThanARunWritesAreNotRead) {
  const fs::path folder = dir_ / "huge";
  fs::create_directories(folder);
  {
    std::ofstream out(folder / "results.json");
    out << "{\"pad\": \"";
  }
  fs::resize_file(folder / "results.json", 600ull << 20);  // sparse: no disk used
  ExpectRefused(Command("export " + folder.string() + " --format json"),
                "results.json: 600 MiB, more than the 256 MiB");
}

// A planned log of 1e10 samples (a sample interval of 0.1 us over a zigzag's duration) is
// refused before a sample is allocated, naming both keys.
TEST_F(CommandLimits, APlannedLogBeyondTheBudgetIsRefused) {
  for (const std::string& planned : {std::string("duration: zigzag_20_20\n  sample_time: 1e-7"),
                                     std::string("duration: 1000\n  sample_time: 1e-7")}) {
    const std::string config = EditedDesignConfig(
        "design:\n  duration: zigzag_20_20\n  sample_time: 0.5", "design:\n  " + planned,
        "design_huge.yaml");
    ExpectRefused(Command("design " + config + " --from " + (dir_ / "run").string()),
                  "design.duration / design.sample_time: a planned log of [0-9.e+]+ samples");
  }
}

// A simulated file named outside --out (a folder part, an absolute path) is refused; the
// file it names stays as it was.
TEST_F(CommandLimits, SimulatedFilesStayInsideOut) {
  std::ofstream(dir_ / "victim.csv") << "precious\n";
  for (const std::string& name : {std::string("../victim.csv"), (dir_ / "victim.csv").string()}) {
    // The simulation section's file, the first in the config.
    const std::string config =
        EditedDesignConfig("file: cargo_zigzag_10.csv", "file: " + name, "outside.yaml");
    ExpectRefused(Command("simulate " + config + " --out " + (dir_ / "sim").string()),
                  "simulation.experiments\\[\\]\\.file: '.*victim\\.csv' is not a plain file name");
    std::ifstream victim(dir_ / "victim.csv");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(victim), std::istreambuf_iterator<char>()),
              "precious\n");
    EXPECT_FALSE(fs::exists(dir_ / "sim"));  // the folder it made for nothing is gone
  }
}

// A steps input held for 1 ms over a 20/20 zigzag's duration: refused, not 300 000 variables.
TEST_F(CommandLimits, ADesignHoldTooShortIsRefused) {
  const std::string config = EditedDesignConfig("hold: 30", "hold: 0.001", "hold.yaml");
  ExpectRefused(Command("design " + config + " --from " + (dir_ / "run").string()),
                "design\\.inputs\\.delta\\.hold: 0\\.001 s over a .* plan makes .* steps");
}

// A correlation matrix cut short or with a diagonal that is not 1, a negative standard error.
TEST_F(CommandLimits, ACorrelationOfTheWrongShapeIsRefused) {
  const std::string cut = EditedRun("cut", [](json* r) {
    for (json& stage : (*r)["stages"]) {
      if (stage.contains("correlation") && stage["correlation"]["names"].size() > 2) {
        stage["correlation"]["names"].erase(stage["correlation"]["names"].size() - 1);
      }
    }
  });
  ExpectRefused(Command("predict " + cut), "not a correlation matrix of its [0-9]+ names");
  const std::string negative = EditedRun("negative", [](json* r) {
    for (json& p : (*r)["parameters"]) {
      if (p["name"] == "K") p["std_error"] = -1.0;
    }
  });
  ExpectRefused(Command("export " + negative + " --format json"), "the std_error of K is negative");
}

// The default --out of export, predict and design (<run>/export, /predict, /design) planted as
// a link to a folder elsewhere: refused, nothing written through it.
TEST_F(CommandLimits, ADefaultFolderThatIsALinkIsRefused) {
  const fs::path run = dir_ / "run", elsewhere = dir_ / "elsewhere";
  fs::create_directories(elsewhere);
  const std::string cargo = std::string(VESSELID_SOURCE_DIR) + "/configs/design_cargo.yaml";
  const std::map<std::string, std::string> commands = {
      {"export", "export " + run.string() + " --format json"},
      {"predict", "predict " + run.string() + " --members 2"},
      {"design", "design " + cargo + " --from " + run.string() + " --quiet"}};
  for (const auto& [name, command] : commands) {
    SCOPED_TRACE(command);
    fs::create_directory_symlink(elsewhere, run / name);
    ExpectRefused(Command(command), "a link, where the default --out of this command is made");
    EXPECT_TRUE(fs::is_empty(elsewhere));
    fs::remove(run / name);
    EXPECT_EQ(Command(command).status, 0);  // made inside the run's folder
    EXPECT_TRUE(fs::is_directory(fs::symlink_status(run / name)));
  }
}

// A full disk (a 17 MiB tmpfs: past the 16 MiB the folder's check asks for, short of the 19 MB
// the cargo campaign's run writes) under a folder holding an earlier set and a user's file: the
// run fails naming the cause, and leaves the earlier set, the user's file and no temporary.
TEST_F(CommandLimits, AFullDiskLeavesTheEarlierSetAndTheUsersFiles) {
  const fs::path disk = dir_ / "disk", out = disk / "out";
  fs::create_directories(disk);
  if (std::system(("mount -t tmpfs -o size=17m tmpfs " + disk.string() + " 2>/dev/null").c_str()) !=
      0) {
    GTEST_SKIP() << "no tmpfs can be mounted here (needs root)";
  }
  struct Unmount {
    fs::path path;
    ~Unmount() { [[maybe_unused]] const int status = std::system(("umount " + path.string()).c_str()); }
  } unmount{disk};
  const std::string source = std::string(VESSELID_SOURCE_DIR) + "/configs/";
  ASSERT_EQ(Command("run " + source + "design_cargo.yaml --data " + (dir_ / "data").string() +
                    " --out " + out.string() + " --quiet --no-report")
                .status,
            0);
  std::ofstream(out / "notes.txt") << "the user's own notes\n";
  std::map<std::string, std::string> before;
  for (const char* name : {"results.json", "report.txt", "notes.txt"}) {
    before[name] = ReadText(out / name);
  }
  const std::string big = (dir_ / "big").string();
  ASSERT_EQ(Command("simulate " + source + "nomoto_cargo.yaml --out " + big).status, 0);
  const CommandOutcome full = Command("run " + source + "nomoto_cargo.yaml --data " + big +
                                     " --out " + out.string() + " --quiet --no-report");
  EXPECT_NE(full.status, 0);
  EXPECT_NE(full.output.find("No space left on device"), std::string::npos) << full.output;
  for (const auto& [name, text] : before) EXPECT_EQ(ReadText(out / name), text) << name;
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    const std::string name = entry.path().filename().string();
    EXPECT_FALSE(name.size() > 4 && name.compare(name.size() - 4, 4, ".tmp") == 0) << name;
    EXPECT_NE(name, ".vesselid-staging");
  }
}

// Each published file of `folder` by its inode: a file of an earlier set keeps the inode it
// was copied to, a file of a new one is renamed in with its own.
std::map<std::string, ino_t> PublishedFiles(const fs::path& folder) {
  std::map<std::string, ino_t> set;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    struct stat info;
    if (!entry.is_regular_file() || name.rfind(".vesselid", 0) == 0 || name == kJournal ||
        ::stat(entry.path().c_str(), &info) != 0) {
      continue;
    }
    set[name] = info.st_ino;
  }
  return set;
}

// A structure selection small enough to kill at every step: two simulated zigzags of the
// cargo ship, its second-order model against a first-order one, two folds by run.
const char kSelectConfig[] = R"(model: {family: nomoto, type: second_order}
simulation:
  truth: {T1: 45.0, T2: 6.0, T3: 10.0, K: 0.09}
  steering_gear: {Tm: 1.0, kp: 0.12, rudder_limit_deg: 35, rate_limit_deg_s: 2.3}
  sample_time: 0.5
  experiments:
    - {file: a.csv, duration: 300, excitation: {type: zigzag, rudder_deg: 10, heading_deg: 10},
       noise: {rudder_deg: 0.1, heading_deg: 0.1}, seed: 21}
    - {file: b.csv, duration: 300, excitation: {type: zigzag, rudder_deg: 20, heading_deg: 20},
       noise: {rudder_deg: 0.1, heading_deg: 0.1}, seed: 22}
experiment_defaults: {inputs: {delta: delta}, outputs: {psi: psi}}
experiments:
  - {name: a, file: a.csv}
  - {name: b, file: b.csv}
stages:
  - &fit
    name: fit
    experiments: [a, b]
    free_initial_states: [psi]
    parameters:
      T1: {start: 60.0, lower: 1.0, upper: 500.0}
      T2: {start: 4.0, lower: 0.1, upper: 100.0}
      T3: {start: 6.0, lower: 0.0, upper: 100.0}
      K: {start: 0.05, lower: 0.001, upper: 2.0}
select:
  experiments: [a, b]
  folds: 2
  candidates:
    - name: second_order
    - name: first_order
      model: {family: nomoto, type: first_order}
      stages:
        - <<: *fit  # the stage with the first-order model's parameters
          parameters: {T: {start: 40.0, lower: 1.0, upper: 500.0},
                       K: {start: 0.05, lower: 0.001, upper: 2.0}}
)";

// `first` then `again` (the same command publishing another set into `out`), `again` killed
// with SIGKILL after every step of its publication: the folder holds one whole set or the other,
// and `again` run whole afterwards ends in a whole set of `files` files. The number of kills.
int KillEveryPublicationStep(const std::string& first, const std::string& again,
                             const fs::path& out, size_t files) {
  const fs::path pristine = out.string() + "_first";
  EXPECT_EQ(Command(first + " --out " + pristine.string()).status, 0) << first;
  EXPECT_EQ(PublishedFiles(pristine).size(), files);
  int kills = 0;
  // Every step up to the exchange and just after it, then every fourth one (the
  // earlier folder's removal, an entry a step: HostileInput kills at each of those).
  for (int step = 1; step < 80; step += step < 6 ? 1 : 4) {
    fs::remove_all(out);
    fs::copy(pristine, out, fs::copy_options::recursive);
    const std::map<std::string, ino_t> a = PublishedFiles(out);
    const CommandOutcome killed =
        testing::RunCommand("VESSELID_TEST_KILL_AT_PUBLISH_STEP=" + std::to_string(step) + " " +
                            VESSELID_BINARY + " " + again + " --out " + out.string());
    if (killed.status == 0) break;
    ++kills;
    SCOPED_TRACE(again + ", killed after step " + std::to_string(step));
    int of_a = 0, of_b = 0;
    for (const auto& [name, inode] : PublishedFiles(out)) {
      const auto found = a.find(name);
      (found != a.end() && found->second == inode ? of_a : of_b) += 1;
    }
    // Only vesselid's outputs in the folder: exchanged whole, so the whole first set or the
    // whole second one at every instant.
    EXPECT_TRUE((of_a == static_cast<int>(a.size()) && of_b == 0) ||
                (of_a == 0 && of_b == static_cast<int>(files)))
        << of_a << " files of the first set beside " << of_b;
    EXPECT_EQ(Command(again + " --out " + out.string()).status, 0);
    // (Not by inode here: the earlier set's, freed, may be the new one's.)
    EXPECT_EQ(PublishedFiles(out).size(), files);
    EXPECT_FALSE(fs::exists(out / ".vesselid-staging"));
  }
  std::printf("%s: %d kills\n", again.substr(0, again.find(' ')).c_str(), kills);
  return kills;
}

// export (three C files), predict (its text and JSON), design (its plan, five files), study
// (study.txt and study.json), select (the chosen candidate's results.json and report.txt) and
// simulate (the tanker campaign's 13 records) over an earlier set of their own, killed at
// every step of the publication.
TEST_F(CommandLimits, EveryCommandKilledWhilePublishingNeverMixesTwoSets) {
  const std::string run = (dir_ / "run").string();
  EXPECT_GE(KillEveryPublicationStep("export " + run + " --format c --seed 1",
                                     "export " + run + " --format c --seed 2", dir_ / "export", 3),
            6);
  EXPECT_GE(KillEveryPublicationStep("predict " + run + " --members 2 --seed 1",
                                     "predict " + run + " --members 2 --seed 2", dir_ / "predict",
                                     2),
            6);
  const std::string cargo = std::string(VESSELID_SOURCE_DIR) + "/configs/design_cargo.yaml";
  const std::string design = "design " + cargo + " --from " + run + " --quiet";
  EXPECT_GE(KillEveryPublicationStep(design, design, dir_ / "design", 5), 6);
  // The shipped cargo config with a study of two start points, on the run's records.
  const fs::path study_config = dir_ / "study.yaml";
  {
    std::ifstream in(cargo);
    std::ofstream out(study_config);
    out << in.rdbuf() << "\nstudy:\n  seed: 1\n  starts: {runs: 2}\n";
  }
  const std::string study =
      "study " + study_config.string() + " --data " + (dir_ / "data").string() + " --quiet";
  EXPECT_GE(KillEveryPublicationStep(study, study, dir_ / "study", 2), 6);
  // select: two zigzags, second against first order, cross-validated by run (0.4 s).
  const fs::path select_config = dir_ / "select" / "select.yaml";
  fs::create_directories(select_config.parent_path());
  std::ofstream(select_config) << kSelectConfig;
  ASSERT_EQ(Command("simulate " + select_config.string() + " --out " +
                    select_config.parent_path().string())
                .status,
            0);
  const std::string select = "select " + select_config.string() + " --quiet --no-report";
  EXPECT_GE(KillEveryPublicationStep(select, select, dir_ / "selected", 2), 6);
  const std::string tanker = std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_tanker.yaml";
  EXPECT_GE(KillEveryPublicationStep("simulate " + tanker, "simulate " + tanker,
                                     dir_ / "simulated", 13),
            6);
}

}  // namespace command_limits_test
}  // namespace vesselid

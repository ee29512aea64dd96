// Hostile input through the command line, as a careless script or a damaged disk produces it:
// every case ends with exit status 1, a message naming the file and line, the key, or the
// experiment and time, nothing partial and no temporary file in --out, and no signal, hang
// or unbounded memory on the way.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "engine/base/atomic_file.h"
#include "engine/output/output_staging.h"
#include "tests/support/bad_input_fixture.h"
#include "tests/support/run_command.h"

namespace vesselid {
namespace hostile_input_test {

namespace fs = std::filesystem;
using testing::BadInput;
using testing::kGoodConfig;
using testing::Outcome;

class HostileInput : public BadInput {
 protected:
  int KillEveryPublicationStep(int min_kills, bool users_file);
  static std::string ReadFile(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  std::string ReadData() { return ReadFile(dir_ / "data.csv"); }
  void WriteData(const std::string& text) { std::ofstream(dir_ / "data.csv") << text; }
  // 1e308 in `column` on line 20: refused with the file, line and column where no mangled cell
  // is accepted (bad_cells: 0; by default it is a gap with a bad_cells finding, see
  // bad_input_test).
  void ExpectHugeValueRefused(const std::string& column) {
    EditConfig("file: data.csv", "file: data.csv\n    bad_cells: 0");
    std::stringstream text(ReadData());
    std::string header, line, edited;
    std::getline(text, header);
    edited = header + "\n";
    std::vector<std::string> names;
    std::stringstream split(header);
    for (std::string name; std::getline(split, name, ',');) names.push_back(name);
    for (int n = 2; std::getline(text, line); ++n) {
      if (n == 20) {
        std::stringstream fields(line);
        line.clear();
        std::string field;
        for (size_t i = 0; std::getline(fields, field, ','); ++i) {
          line += (i ? "," : "") + (names[i] == column ? std::string("1e308") : field);
        }
      }
      edited += line + "\n";
    }
    WriteData(edited);
    ExpectRejected("data\\.csv:20: column '" + column + "': 1e308 is too large for a measurement");
  }
  // Largest resident set of any child process so far (vesselid under popen's shell), MiB.
  static double ChildPeakMiB() {
    struct rusage usage;
    ::getrusage(RUSAGE_CHILDREN, &usage);
    return usage.ru_maxrss / 1024.0;
  }
  // Appends a column `name` to data.csv, its cell on data line n (2: the first row) cell(n, row).
  void AppendColumn(const std::string& name,
                    const std::function<std::string(int, const std::string&)>& cell) {
    std::stringstream text(ReadData());
    std::string line, edited;
    for (int n = 1; std::getline(text, line); ++n) {
      edited += line + "," + (n == 1 ? name : cell(n, line)) + "\n";
    }
    WriteData(edited);
  }
  // The data's last line (1-based).
  int LastLine() {
    const std::string text = ReadData();
    return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  }
};

// --- Reads: regular files only, within limits -------------------------------------------

TEST_F(HostileInput, DataFileIsAFolder) {
  fs::remove(dir_ / "data.csv");
  fs::create_directory(dir_ / "data.csv");
  ExpectRejected("data\\.csv: is a folder, not a data file");
}

TEST_F(HostileInput, ConfigFileIsAFolder) {
  fs::remove(dir_ / "config.yaml");
  fs::create_directory(dir_ / "config.yaml");
  ExpectRejected("config\\.yaml: is a folder, not a config file");
}

TEST_F(HostileInput, DataFileIsADevice) {
  fs::remove(dir_ / "data.csv");
  fs::create_symlink("/dev/zero", dir_ / "data.csv");
  // A link out of the data folder leaves it; allowed, the device is still no data file.
  ExpectRejected("'data\\.csv' is outside the data folder");
  WriteConfig(std::string(kGoodConfig) + "limits: {outside_data: true}\n");
  ExpectRejected("data\\.csv: is a character device, not a data file");
}

TEST_F(HostileInput, DataFileIsANamedPipeWithNoWriter) {
  fs::remove(dir_ / "data.csv");
  ASSERT_EQ(::mkfifo((dir_ / "data.csv").c_str(), 0600), 0);
  // A hang would end in timeout's status 124 and no message.
  const Outcome outcome =
      ExpectRejected("data\\.csv: is a named pipe, not a data file", "timeout 60 ");
  EXPECT_NE(outcome.status >> 8, 124);
}

TEST_F(HostileInput, SparseFileLargerThanTheLimitIsNotRead) {
  std::ofstream(dir_ / "data.csv", std::ios::app).flush();
  fs::resize_file(dir_ / "data.csv", std::uintmax_t{2} << 30);  // sparse: no disk used
  ExpectRejected(
      "data\\.csv: the data file is 2\\.0 GiB, more than the limit of 1\\.0 GiB "
      "\\(limits\\.file_mb\\)");
  EXPECT_LT(ChildPeakMiB(), 1024.0);  // never read (the fingerprint used to read it whole)
}

// With file_mb raised, a 1.25 GiB line (a sparse file after the header) is refused at 16 MiB,
// not mapped or read whole first (the checkpoint's fingerprint still reads it, streaming:
// 2.4 s of the test).
TEST_F(HostileInput, ALineOfGigabytesIsRefusedAtTheLineLimit) {
  std::ofstream(dir_ / "data.csv") << "t,delta,psi\n0,0,0\n";
  fs::resize_file(dir_ / "data.csv", std::uintmax_t{5} << 28);  // sparse: no disk used
  WriteConfig(std::string(kGoodConfig) + "limits: {file_mb: 4096}\n");
  ExpectRejected("data\\.csv:3: line longer than 16 MiB");
  EXPECT_LT(ChildPeakMiB(), 1024.0);
}

// 5 000 000 nested [ in a 5 MB config: refused before yaml-cpp tokenises it.
TEST_F(HostileInput, DeeplyNestedConfigIsRefusedBeforeItIsParsed) {
  WriteConfig(std::string(kGoodConfig) + "description: " + std::string(5000000, '[') + "\n");
  ExpectRejected("config\\.yaml:13: YAML lists or maps nested deeper than 64 levels");
  EXPECT_LT(ChildPeakMiB(), 1024.0);
}

TEST_F(HostileInput, ValidHeadOfAFileLargerThanTheLimit) {
  std::string text = ReadData();
  const std::string row = text.substr(text.rfind('\n', text.size() - 2) + 1);
  double t = 1000.0;
  while (text.size() < (3u << 19)) {  // 1.5 MiB of valid rows
    text += std::to_string(t) + row.substr(row.find(','));
    t += 0.1;
  }
  WriteData(text);
  WriteConfig(std::string(kGoodConfig) + "limits: {file_mb: 1}\n");
  ExpectRejected(
      "data\\.csv: the data file is 1\\.5 MiB, more than the limit of 1\\.0 MiB "
      "\\(limits\\.file_mb\\)");
}

TEST_F(HostileInput, MoreValuesThanTheLimit) {
  WriteConfig(std::string(kGoodConfig) + "limits: {data_values: 100}\n");
  ExpectRejected(
      "data\\.csv:[0-9]+: more than 100 values \\(rows x columns\\) in one data "
      "file \\(limits\\.data_values\\)");
}

// --- Work size: refused before the first stage, with the number and the key -------------

TEST_F(HostileInput, IntegrationStepTooSmall) {
  EditConfig("    free_initial_states: [psi]\n",
             "    free_initial_states: [psi]\n    integration: {max_step: 1.0e-7}\n");
  ExpectRejected(
      "experiment 'run' .*data\\.csv.*stage 'fit' integrates 60 s of it in steps "
      "of at most 1e-07 s \\(stages\\[0\\]\\.integration\\.max_step\\): 6e\\+08 "
      "integration steps, more than the limit of 2e\\+07 "
      "\\(limits\\.integration_steps\\)");
}

// Raising limits.integration_steps does not remove the guard: the memory budget refuses the
// steps' input caches before they are allocated, on any machine (2.9 TB).
TEST_F(HostileInput, RaisedStepLimitIsStillBoundedByTheMemoryBudget) {
  EditConfig("    free_initial_states: [psi]\n",
             "    free_initial_states: [psi]\n    integration: {max_step: 1.0e-9}\n"
             "limits: {integration_steps: 1e15}\n");
  ExpectRejected(
      "stage 'fit': its experiments need [0-9.]+ TiB, more than the memory budget of "
      "[0-9.]+ [GT]iB \\(limits\\.memory_mb\\) \\(the records read [0-9.]+ KiB, input caches of "
      "6e\\+10 integration steps [0-9.]+ TiB.*stages\\[0\\]\\.integration\\.max_step");
  EXPECT_LT(ChildPeakMiB(), 200.0);
}

// limits.memory_mb is the budget: 1 MiB refuses 6e6 steps (183 MiB of input caches) that
// the default budget and limits.integration_steps (2e7) admit.
TEST_F(HostileInput, MemoryBudgetIsTheConfigs) {
  EditConfig("    free_initial_states: [psi]\n",
             "    free_initial_states: [psi]\n    integration: {max_step: 1.0e-5}\n"
             "limits: {memory_mb: 1}\n");
  ExpectRejected("more than the memory budget of 1 MiB \\(limits\\.memory_mb\\)");
}

// limits.memory_mb above the machine's memory is held to 90 % of it: 6e9 steps (about 180 GiB
// of input caches) under a budget of 1 TiB are refused, not met with std::bad_alloc.
TEST_F(HostileInput, MemoryBudgetAboveTheMachinesIsHeldToIt) {
  EditConfig("    free_initial_states: [psi]\n",
             "    free_initial_states: [psi]\n    integration: {max_step: 1.0e-8}\n"
             "limits: {memory_mb: 1048576, integration_steps: 1e10}\n");
  ExpectRejected("\\(limits\\.memory_mb, held to 90 % of this machine's memory\\)");
  EXPECT_LT(ChildPeakMiB(), 1024.0);
}

TEST_F(HostileInput, AbsurdLastTimeIsRefusedBeforeTheRun) {
  const std::string text = ReadData();
  const std::string row = text.substr(text.rfind('\n', text.size() - 2) + 1);
  WriteData(text + "1e50" + row.substr(row.find(',')));
  ExpectRejected(
      "1e\\+50 s of it in steps of at most 0\\.1 s \\(the median sample interval; "
      "check the file's t column\\).*limits\\.integration_steps");
}

TEST_F(HostileInput, StudyRunsPastTheLimit) {
  WriteConfig(std::string(kGoodConfig) +
              "study:\n  monte_carlo: {stage: fit, runs: 1000000000, noise: {psi: 0.01}}\n");
  ExpectRejected(
      "config\\.yaml:14: study\\.monte_carlo\\.runs: 1e\\+09 is more than the limit "
      "of 100000 \\(limits\\.study_cases\\)");
}

TEST_F(HostileInput, GlobalEvaluationsPastTheLimit) {
  EditConfig("    free_initial_states: [psi]\n",
             "    free_initial_states: [psi]\n    global: {max_evaluations: 2000000000}\n");
  ExpectRejected(
      "config\\.yaml:13: stages\\[0\\]\\.global\\.max_evaluations: 2e\\+09 is more "
      "than the limit of 1e\\+07 \\(limits\\.evaluations\\)");
}

// --- Overflow: refused at read time with file, line and column --------------------------

TEST_F(HostileInput, WeightsThatOverflowTheCost) {
  EditConfig("    outputs: {psi: psi}\n", "    outputs: {psi: psi}\n    weights: {psi: 1.0e300}\n");
  ExpectRejected("experiment 'run' .*weights\\.psi = 1e\\+300 makes the cost overflow");
}

TEST_F(HostileInput, HugeOutputValue) { ExpectHugeValueRefused("psi"); }

TEST_F(HostileInput, HugeInputValue) { ExpectHugeValueRefused("delta"); }

TEST_F(HostileInput, HugeTime) {
  const std::string text = ReadData();
  const std::string row = text.substr(text.rfind('\n', text.size() - 2) + 1);
  WriteData(text + "1e308" + row.substr(row.find(',')));
  ExpectRejected("data\\.csv:" + std::to_string(LastLine()) +
                 ": column 't': 1e308 is too large for a measurement");
}

// A start whose mass matrix is indefinite (m - Xudot < 0) names the experiment, the time, the
// inputs there and the broken condition.
TEST_F(HostileInput, IndefiniteMassMatrixAtTheStartIsNamed) {
  WriteConfig(R"(model: {family: erunsal6dof}
simulation:
  sample_time: 0.05
  substeps: 2
  experiments:
    - {file: zigzag.csv, type: zigzag, duration: 20, mean_command: 0.6, differential: 0.4, zigzag_heading_deg: 20, seed: 61, active_dofs: [surge, sway, yaw]}
experiments:
  - {name: zigzag, file: zigzag.csv, inputs: {c_L: c_L, c_R: c_R}, outputs: {x: x, y: y, psi: psi}}
stages:
  - name: manoeuvre
    model: {active_dofs: [surge, sway, yaw]}
    experiments: [zigzag]
    free_initial_states: [u, v, r]
    parameters:
      Xudot: {start: 20.0, lower: -10.0, upper: 30.0}
)");
  const std::string simulate = std::string(VESSELID_BINARY) + " simulate " +
                               (dir_ / "config.yaml").string() + " --out " + dir_.string() +
                               " > /dev/null";
  ASSERT_EQ(std::system(simulate.c_str()), 0);
  ExpectRejected(
      "stage 'manoeuvre': .*simulation of experiment 'zigzag' diverges after t = 0 "
      "s; .*u.* not finite at t = 0\\.05 s \\(inputs at t = 0 s: c_L = .*, c_R = "
      "[^,]*\\); at these values M is not positive definite .*: m - Xudot = 11 - 20 "
      "<= 0");
}

// `vesselid simulate` publishes its files as one set (output_staging.h): no staging folder is
// left, the set's manifest lists them, simulating the config again replaces what it wrote
// (a file it no longer writes goes), and another config's files in the folder stay.
TEST_F(HostileInput, SimulatedFilesArePublishedAsOneSetPerConfig) {
  auto write = [&](const std::string& name, const std::vector<std::string>& files) {
    std::string text = "model: {family: nomoto, type: second_order}\nsimulation:\n"
                       "  truth: {T1: 45.0, T2: 6.0, T3: 10.0, K: 0.09}\n"
                       "  steering_gear: {Tm: 5.0, kp: 0.12, rudder_limit_deg: 35}\n"
                       "  sample_time: 0.5\n  experiments:\n";
    for (const std::string& f : files) {
      text += "    - {file: " + f + ", duration: 60, excitation: {type: sine, amplitude_deg: "
              "20, period: 30}}\n";
    }
    text += "experiments:\n";
    for (const std::string& f : files) {
      text += "  - {name: " + f.substr(0, f.size() - 4) + ", file: " + f +
              ", inputs: {delta: delta}, outputs: {psi: psi}}\n";
    }
    text += "stages:\n  - name: fit\n    parameters:\n      K: {start: 0.1, lower: 0.01, upper: 1}\n";
    std::ofstream(dir_ / name) << text;
  };
  const fs::path out = dir_ / "sim";
  auto simulate = [&](const std::string& config) {
    const std::string command = std::string(VESSELID_BINARY) + " simulate " +
                                (dir_ / config).string() + " --out " + out.string() +
                                " > /dev/null 2>&1";
    return std::system(command.c_str());
  };
  write("first.yaml", {"a.csv", "b.csv"});
  write("second.yaml", {"c.csv"});
  ASSERT_EQ(simulate("first.yaml"), 0);
  ASSERT_EQ(simulate("second.yaml"), 0);
  EXPECT_TRUE(fs::exists(out / "a.csv") && fs::exists(out / "b.csv") && fs::exists(out / "c.csv"));
  EXPECT_FALSE(fs::exists(out / kStagingFolder));
  std::ifstream manifest(out / ".vesselid-simulate.first.set");
  const std::string listed((std::istreambuf_iterator<char>(manifest)), {});
  EXPECT_EQ(listed, "a.csv\nb.csv\n");
  write("first.yaml", {"a.csv"});
  ASSERT_EQ(simulate("first.yaml"), 0);
  EXPECT_TRUE(fs::exists(out / "a.csv"));
  EXPECT_FALSE(fs::exists(out / "b.csv"));
  EXPECT_TRUE(fs::exists(out / "c.csv"));
}

// --- YAML and CSV dialects ----------------------------------------------------------------

TEST_F(HostileInput, DuplicateYamlKeyNamesBothLines) {
  WriteConfig(std::string(kGoodConfig) + "model: {family: nomoto, type: second_order}\n");
  ExpectRejected("config\\.yaml:13: model: given twice \\(lines 1 and 13\\)");
}

TEST_F(HostileInput, DuplicateNestedKey) {
  EditConfig("      K: {start", "      T: {start: 4.0}\n      K: {start");
  ExpectRejected(
      "config\\.yaml:11: stages\\[0\\]\\.parameters\\.T: given twice \\(lines 10 "
      "and 11\\)");
}

// --- Names that become file names ---------------------------------------------------------

// Experiments "a/b" and "a_b" each get their own trace (both were written to fit.a_b.csv, one
// overwriting the other): names are escaped reversibly in file names.
TEST_F(HostileInput, NamesThatLookAlikeInFileNamesKeepTheirOwnFiles) {
  std::string text = kGoodConfig;
  text.replace(text.find("name: run"), 9, "name: a/b");
  text.replace(text.find("stages:"), 7,
               "  - {name: a_b, file: data.csv, inputs: {delta: delta}, outputs: {psi: psi}}\n"
               "stages:");
  WriteConfig(text);
  const Outcome outcome = Run();
  ASSERT_EQ(outcome.status, 0) << outcome.output;
  std::set<std::string> traces;
  for (const auto& entry : fs::directory_iterator(dir_ / "out" / "traces")) {
    traces.insert(entry.path().filename().string());
  }
  EXPECT_EQ(traces, (std::set<std::string>{"fit.a%2Fb.csv", "fit.a_b.csv"}));
}

TEST_F(HostileInput, NameWithANewlineIsRefused) {
  EditConfig("  - name: run\n", "  - name: \"ru\\nn\"\n");
  ExpectRejected(
      "config\\.yaml:3: experiments\\[0\\]\\.name: the name holds a control "
      "character \\(0x0a\\)");
}

// A 5 000-byte name was computed, then failed at its trace with "cannot write file".
TEST_F(HostileInput, NameTooLongForAFileNameIsRefused) {
  EditConfig("  - name: fit\n", "  - name: " + std::string(5000, 'f') + "\n");
  ExpectRejected(
      "config\\.yaml:8: stages\\[0\\]\\.name: the name has 5000 bytes \\(5000 in a "
      "file name\\), more than the 115 a name may have");
}

// --- Many files, many experiments, files elsewhere ------------------------------------------

// A pattern matching more files than limits.files (default 10 000) is refused while it is
// expanded, before any file is read (100 000 matching logs took 8.2 GB and a SIGABRT).
TEST_F(HostileInput, PatternMatchingTooManyFilesIsRefusedBeforeReadingThem) {
  fs::create_directories(dir_ / "logs");
  for (int i = 0; i <= 10000; ++i)
    std::ofstream(dir_ / "logs" / ("f_" + std::to_string(i) + ".csv"));
  EditConfig("  - name: run\n    file: data.csv\n", "  - files: \"logs/f_*.csv\"\n");
  ExpectRejected(
      "config\\.yaml:3: experiments\\[0\\]\\.files: 'logs/f_\\*\\.csv' matches 10001 "
      "files, more than the 10000 a run may read \\(limits\\.files\\)");
  EXPECT_LT(ChildPeakMiB(), 200.0);
}

TEST_F(HostileInput, MoreExperimentsThanTheLimit) {
  std::string entries;
  for (int i = 0; i < 5; ++i) {
    entries += "  - {name: w" + std::to_string(i) + ", file: data.csv, window: [0, " +
               std::to_string(10 + i) + "], inputs: {delta: delta}, outputs: {psi: psi}}\n";
  }
  std::string text = kGoodConfig;
  text.replace(text.find("stages:"), 7, entries + "stages:");
  WriteConfig(text + "limits: {experiments: 4}\n");
  ExpectRejected(
      "experiments\\[4\\]: more than 4 experiments, the limit \\(limits\\.experiments\\)");
}

// Data files stay in the data folder unless the config allows otherwise: a copy of the data
// beside the test's folder, named by a path and by a pattern; allowed, each is a finding.
TEST_F(HostileInput, DataFilesOutsideTheDataFolderNeedOutsideData) {
  const std::string name = dir_.filename().string() + "_outside.csv";
  fs::copy_file(dir_ / "data.csv", dir_.parent_path() / name, fs::copy_options::overwrite_existing);
  EditConfig("file: data.csv", "file: ../" + name);
  ExpectRejected("experiments\\[0\\]\\.file: '\\.\\./" + name +
                 "' is outside the data folder .*limits: \\{outside_data: true\\}");
  EditConfig("  - name: run\n    file: data.csv\n",
             "  - files: \"../" + dir_.filename().string() + "_outside*.csv\"\n");
  ExpectRejected("experiments\\[0\\]\\.files: '\\.\\./.*_outside\\*\\.csv' matches '\\.\\./" +
                 name + "' is outside the data folder");
  std::string text = kGoodConfig;
  text.replace(text.find("file: data.csv"), 14, "file: ../" + name);
  WriteConfig(text + "limits: {outside_data: true}\n");
  const Outcome outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
  // Allowed, and said: a finding names the file and the folder it left.
  const std::string results = ReadFile(dir_ / "out" / "results.json");
  EXPECT_NE(results.find("outside_data_folder"), std::string::npos);
  EXPECT_NE(results.find("read '" + (dir_.parent_path() / name).string() +
                         "', outside the data folder " + dir_.string()),
            std::string::npos)
      << results;
  EXPECT_NE(ReadFile(dir_ / "out" / "report.txt").find("outside_data_folder"), std::string::npos);
  // A file inside the folder under the same limits is not one.
  WriteConfig(std::string(kGoodConfig) + "limits: {outside_data: true}\n");
  ASSERT_EQ(Run().status, 0);
  EXPECT_EQ(ReadFile(dir_ / "out" / "results.json").find("outside_data_folder"), std::string::npos);
  fs::remove(dir_.parent_path() / name);
}

// A link inside the data folder to a file, or to a folder, outside it leaves the folder as
// "../" does.
TEST_F(HostileInput, LinksOutOfTheDataFolderAreOutside) {
  const fs::path elsewhere = dir_.string() + "_elsewhere";
  fs::remove_all(elsewhere);
  fs::create_directories(elsewhere);
  fs::copy_file(dir_ / "data.csv", elsewhere / "data.csv");
  fs::create_symlink(elsewhere / "data.csv", dir_ / "linked.csv");
  EditConfig("file: data.csv", "file: linked.csv");
  ExpectRejected("'linked\\.csv' is outside the data folder");
  fs::create_directory_symlink(elsewhere, dir_ / "linked_folder");
  EditConfig("file: data.csv", "file: linked_folder/data.csv");
  ExpectRejected("'linked_folder/data\\.csv' is outside the data folder");
  fs::remove_all(elsewhere);
}

// --- Where the results go ----------------------------------------------------------------

TEST_F(HostileInput, OutEmptyOrTheRootFolderIsRefused) {
  ExpectRejected("--out is empty: name a folder for the results", "", "''");
  const Outcome root = Run("", "/");
  EXPECT_NE(root.status, 0);
  EXPECT_NE(root.output.find("/: --out is the root folder: name a folder of its own for the "
                             "results"),
            std::string::npos)
      << root.output;
  EXPECT_FALSE(fs::exists("/results.json") || fs::exists("/.vesselid"));
}

// A folder of other files is not an output folder; an earlier output is (its marker).
TEST_F(HostileInput, OutHoldingOtherFilesIsRefusedAnEarlierOutputIsNot) {
  fs::create_directories(dir_ / "out");
  std::ofstream(dir_ / "out" / "notes.txt") << "field notes\n";
  ExpectRejected("--out holds other files \\('notes\\.txt'\\) and no earlier vesselid output");
  EXPECT_TRUE(fs::exists(dir_ / "out" / "notes.txt"));
  fs::remove(dir_ / "out" / "notes.txt");
  Outcome outcome = Run();
  ASSERT_EQ(outcome.status, 0) << outcome.output;
  EXPECT_TRUE(fs::exists(dir_ / "out" / ".vesselid"));
  std::ofstream(dir_ / "out" / "notes.txt") << "field notes\n";
  outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
}

// --out the config's own folder, which holds the user's traces/, surfaces/, report.txt and
// notes.txt: the run is refused before any work, naming what is in the way, and every byte
// stays. A report.txt of the user's own does not make the folder an earlier output.
TEST_F(HostileInput, UsersFilesBesideAndInsideOutSurvive) {
  std::map<std::string, std::string> mine = {{"traces/gps_2026.csv", "t,lat\n0,59.9\n"},
                                                   {"surfaces/hull.stl", "solid hull\n"},
                                                   {"report.txt", "my own report\n"},
                                                   {"notes.txt", "field notes\n"}};
  auto plant = [&]() {
    for (const auto& [name, text] : mine) {
      fs::create_directories((dir_ / name).parent_path());
      std::ofstream(dir_ / name) << text;
    }
  };
  auto check = [&]() {
    for (const auto& [name, text] : mine) EXPECT_EQ(ReadFile(dir_ / name), text) << name;
  };
  plant();
  Outcome outcome = Run("", dir_);
  EXPECT_NE(outcome.status, 0);
  EXPECT_NE(outcome.output.find("but did not write it"), std::string::npos) << outcome.output;
  EXPECT_FALSE(fs::exists(dir_ / "results.json"));
  check();
  // Without the sub-folders in the way, report.txt still is.
  fs::remove_all(dir_ / "traces");
  fs::remove_all(dir_ / "surfaces");
  mine.erase("traces/gps_2026.csv");
  mine.erase("surfaces/hull.stl");
  outcome = Run("", dir_);
  EXPECT_NE(outcome.status, 0);
  EXPECT_NE(outcome.output.find("report.txt: vesselid would replace this"), std::string::npos)
      << outcome.output;
  check();
  // With room, the run writes beside them, and runs again over its own outputs only.
  fs::remove(dir_ / "report.txt");
  outcome = Run("", dir_);
  ASSERT_EQ(outcome.status, 0) << outcome.output;
  std::ofstream(dir_ / "traces" / "my_notes.txt") << "mine\n";  // inside an output folder
  outcome = Run("", dir_);
  EXPECT_NE(outcome.status, 0);
  EXPECT_EQ(ReadFile(dir_ / "traces" / "my_notes.txt"), "mine\n");
  EXPECT_EQ(ReadFile(dir_ / "notes.txt"), "field notes\n");
}

// kill -9 at every step of the publication (VESSELID_TEST_KILL_AT_PUBLISH_STEP: the process
// sends itself SIGKILL after that many removals, moves, exchanges and manifest writes), in
// rounds until `min_kills`: the folder never holds files of both sets, and the next command
// finishes the publication into the whole new set. With nothing but vesselid's outputs in the
// folder the set is exchanged whole (the whole of set A or of set B at every instant); with a
// user's file beside them it is published entry by entry (results.json only over a whole set),
// and the user's file is kept. The number of kills.
int HostileInput::KillEveryPublicationStep(int min_kills, bool users_file) {
  const fs::path dir = dir_, out = dir_ / "out", pristine = dir_ / "set_a";
  EXPECT_EQ(Run("", pristine).status, 0);
  if (users_file) std::ofstream(pristine / "notes.txt") << "field notes\n";
  // Every file of a set but the folder's bookkeeping and the user's, with its content.
  auto files = [](const fs::path& folder) {
    std::map<std::string, std::string> set;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
      const std::string relative = entry.path().lexically_relative(folder).string();
      if (!entry.is_regular_file() || relative.rfind(".vesselid", 0) == 0 ||
          relative == kJournal || relative == "notes.txt" || relative.rfind("checkpoint", 0) == 0) {
        continue;
      }
      set[relative] = ReadFile(entry.path());
    }
    return set;
  };
  const std::map<std::string, std::string> a = files(pristine);
  EditConfig("name: fit", "name: refit");  // set B: other trace names, other results
  EXPECT_EQ(Run("", dir / "set_b").status, 0);
  std::set<std::string> b_names;
  for (const auto& [name, text] : files(dir / "set_b")) b_names.insert(name);
  int kills = 0;
  for (int round = 0; kills < min_kills && round < 20; ++round) {
    for (int step = 1;; ++step) {
      fs::remove_all(out);
      fs::copy(pristine, out, fs::copy_options::recursive);
      const Outcome killed =
          Run("VESSELID_TEST_KILL_AT_PUBLISH_STEP=" + std::to_string(step) + " ", out);
      if (killed.status == 0) break;  // the publication has fewer steps
      ++kills;
      SCOPED_TRACE("killed after step " + std::to_string(step));
      int of_a = 0, of_b = 0;
      const std::map<std::string, std::string> now = files(out);
      std::set<std::string> names;
      for (const auto& [name, text] : now) {
        const auto found = a.find(name);
        (found != a.end() && found->second == text ? of_a : of_b) += 1;
        names.insert(name);
      }
      EXPECT_FALSE(of_a > 0 && of_b > 0) << of_a << " files of set A beside " << of_b << " of B";
      if (!users_file) {
        EXPECT_TRUE(now == a || (of_a == 0 && names == b_names))
            << of_a << " files of set A, " << of_b << " of B (of " << b_names.size() << ")";
      } else if (now.count("results.json") != 0) {
        EXPECT_TRUE(now == a || names == b_names) << "results.json beside a partial set";
      }
      const Outcome next = Run("", out);
      EXPECT_EQ(next.status, 0) << next.output;
      names.clear();
      for (const auto& [name, text] : files(out)) names.insert(name);
      EXPECT_EQ(names, b_names);
      EXPECT_FALSE(fs::exists(out / kStagingFolder));
      if (users_file) EXPECT_EQ(ReadFile(out / "notes.txt"), "field notes\n");
    }
  }
  std::printf("%d kills (%s)\n", kills, users_file ? "beside a user's file" : "exchanged whole");
  return kills;
}

TEST_F(HostileInput, KilledAtEveryStepOfThePublicationNeverMixesTwoSets) {
  EXPECT_GE(KillEveryPublicationStep(50, /*users_file=*/false), 50);
}

TEST_F(HostileInput, KilledBesideAUsersFileNeverMixesTwoSetsAndKeepsTheFile) {
  EXPECT_GE(KillEveryPublicationStep(1, /*users_file=*/true), 10);
}

// --resume finds the checkpoint of the same config and data named by other spellings of
// their paths (compared canonically).
TEST_F(HostileInput, ResumeKnowsTheSameFilesByAnotherSpelling) {
  ASSERT_EQ(Run().status, 0);
  const testing::CommandOutcome resumed =
      testing::RunCommand(std::string(VESSELID_BINARY) + " run " + dir_.string() +
                          "/./config.yaml --out " + dir_.string() + "/./out/ --resume");
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_EQ(resumed.output.find("another config or other data"), std::string::npos)
      << resumed.output;
}

// A checkpoint/ no manifest names (as an earlier vesselid left it beside its results) is
// vesselid's by its own manifest: the next run takes it over (--resume goes on from it) and
// publishes its own, named by the set's manifest, in its place.
TEST_F(HostileInput, ACheckpointNoManifestNamesIsTakenOver) {
  ASSERT_EQ(Run().status, 0);
  const fs::path out = dir_ / "out", manifest = out / ".vesselid-run.set";
  std::string kept;
  {
    std::ifstream in(manifest);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("checkpoint", 0) != 0) kept += line + "\n";
    }
  }
  std::ofstream(manifest, std::ios::trunc) << kept;
  const testing::CommandOutcome resumed = testing::RunCommand(std::string(VESSELID_BINARY) + " run " +
                                              (dir_ / "config.yaml").string() + " --out " +
                                              out.string() + " --resume");
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming after stage"), std::string::npos) << resumed.output;
  EXPECT_NE(ReadFile(manifest).find("checkpoint/manifest.json"), std::string::npos);
  EXPECT_FALSE(fs::exists(out / kWorkingCheckpoint));
}

// A working checkpoint a kill left half made or half removed (no manifest: only a stage file,
// only the manifest's temporary, nothing) is vesselid's: the next run replaces it.
TEST_F(HostileInput, AHalfMadeWorkingCheckpointIsReplaced) {
  ASSERT_EQ(Run().status, 0);
  const fs::path working = dir_ / "out" / kWorkingCheckpoint;
  for (const std::string& left : {"stage_001.cbor", "manifest.json.tmp", ""}) {
    SCOPED_TRACE(left.empty() ? "empty" : left);
    fs::remove_all(working);
    fs::create_directories(working);
    if (!left.empty()) std::ofstream(working / left) << "partial";
    const Outcome outcome = Run();
    EXPECT_EQ(outcome.status, 0) << outcome.output;
    EXPECT_FALSE(fs::exists(working));
  }
}

// --resume of another config over a published checkpoint is refused and leaves no working
// checkpoint behind.
TEST_F(HostileInput, ARefusedResumeLeavesNoWorkingCheckpoint) {
  ASSERT_EQ(Run().status, 0);
  EditConfig("name: fit", "name: refit");
  const testing::CommandOutcome resumed = testing::RunCommand(
      std::string(VESSELID_BINARY) + " run " + (dir_ / "config.yaml").string() + " --out " +
      (dir_ / "out").string() + " --resume");
  EXPECT_NE(resumed.status, 0);
  EXPECT_NE(resumed.output.find("another config or other data"), std::string::npos)
      << resumed.output;
  EXPECT_FALSE(fs::exists(dir_ / "out" / kWorkingCheckpoint));
}

// While another vesselid process holds the folder, a refusal says so, not what that process is
// writing there (its outputs in the way, its checkpoint at work).
TEST_F(HostileInput, ARefusalWhileAnotherProcessWritesNamesIt) {
  ASSERT_EQ(Run().status, 0);
  std::ofstream(dir_ / "out" / "traces" / "theirs.csv") << "t\n";  // in the way of this run
  const int fd = ::open((dir_ / "out" / ".vesselid.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  const Outcome outcome = Run();
  ::close(fd);
  EXPECT_NE(outcome.status, 0);
  EXPECT_NE(outcome.output.find("another vesselid process"), std::string::npos) << outcome.output;
  fs::remove(dir_ / "out" / "traces" / "theirs.csv");
}

// A file the user puts into the run's checkpoint folder, and a link planted at the name of a
// manifest's temporary, are theirs: the next run refuses, or removes the link without writing
// through it.
TEST_F(HostileInput, CheckpointAndTemporariesOfTheUsersAreKept) {
  ASSERT_EQ(Run().status, 0);
  std::ofstream(dir_ / "out" / "checkpoint" / "notes.txt") << "mine\n";
  Outcome outcome = Run();
  EXPECT_NE(outcome.status, 0);
  EXPECT_NE(outcome.output.find("checkpoint/notes.txt: vesselid keeps a run's checkpoint"),
            std::string::npos)
      << outcome.output;
  EXPECT_EQ(ReadFile(dir_ / "out" / "checkpoint" / "notes.txt"), "mine\n");
  fs::remove(dir_ / "out" / "checkpoint" / "notes.txt");
  std::ofstream(dir_ / "victim.txt") << "precious\n";
  fs::create_symlink(dir_ / "victim.txt", dir_ / "out" / ".vesselid-run.set.tmp");
  outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
  EXPECT_EQ(ReadFile(dir_ / "victim.txt"), "precious\n");
  EXPECT_FALSE(fs::is_symlink(dir_ / "out" / ".vesselid-run.set"));
}

// A link planted at the staging folder's name (to a forged journal and a file outside --out)
// and at the lock's name: neither is followed; the files they point to stay as they were.
TEST_F(HostileInput, LinksPlantedInOutAreNotFollowed) {
  ASSERT_EQ(Run().status, 0);
  const fs::path outside = dir_ / "outside";
  fs::create_directories(outside);
  std::ofstream(outside / "precious.csv") << "keep\n";
  std::ofstream(outside / kJournal) << "set run\nlast precious.csv\nentry precious.csv\n";
  std::ofstream(outside / "lock_target") << "keep too\n";
  fs::create_directory_symlink(outside, dir_ / "out" / kStagingFolder);
  fs::create_symlink(outside / "lock_target", dir_ / "out" / ".vesselid.lock");
  const Outcome outcome = Run();
  EXPECT_EQ(ReadFile(outside / "precious.csv"), "keep\n");
  EXPECT_EQ(ReadFile(outside / "lock_target"), "keep too\n");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "precious.csv"));
  (void)outcome;  // refused (the lock is a link) or run: either way nothing outside moved
}

// --out a parent of the config's (and data's) folder: its outputs would mix with them.
TEST_F(HostileInput, OutAParentOfTheDataIsRefused) {
  fs::create_directories(dir_ / "campaign");
  for (const char* file : {"config.yaml", "data.csv"})
    fs::rename(dir_ / file, dir_ / "campaign" / file);
  const std::string command = std::string(VESSELID_BINARY) + " run " +
                              (dir_ / "campaign" / "config.yaml").string() + " --out " +
                              dir_.string() + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe) != nullptr) output += buffer;
  EXPECT_NE(pclose(pipe), 0);
  EXPECT_TRUE(std::regex_search(
      output, std::regex("--out holds the inputs' folder .*campaign .*: choose a folder beside "
                         "or inside it")))
      << output;
  EXPECT_FALSE(fs::exists(dir_ / "results.json") || fs::exists(dir_ / ".vesselid"));
}

TEST_F(HostileInput, ByteOrderMarksAreAccepted) {
  WriteConfig("\xEF\xBB\xBF" + std::string(kGoodConfig));
  WriteData("\xEF\xBB\xBF" + ReadData());
  const Outcome outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "results.json"));
}

TEST_F(HostileInput, SemicolonSeparatorIsNamed) {
  std::string text = ReadData();
  std::replace(text.begin(), text.end(), ',', ';');
  WriteData(text);
  ExpectRejected(
      "data\\.csv:1: the header is separated by ';', not ',': convert the file to "
      "commas or set the experiment's separator: \";\"");
  EditConfig("    file: data.csv\n", "    file: data.csv\n    separator: \";\"\n");
  const Outcome outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
}

// A note column as pandas writes it: quoted where it holds the separator or a quote (RFC 4180).
TEST_F(HostileInput, QuotedFieldsHoldingTheSeparatorAreRead) {
  AppendColumn("note", [](int n, const std::string&) {
    return n == 5 ? std::string("\"turned, then \"\"steady\"\"\"") : std::string();
  });
  const Outcome outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
}

// A second time column is named a duplicate, also where the config reads named columns only.
TEST_F(HostileInput, ASecondTimeColumnIsADuplicate) {
  AppendColumn("t", [](int, const std::string& row) { return row.substr(0, row.find(',')); });
  ExpectRejected("data\\.csv:1: duplicate column 't' \\(the time\\)");
}

TEST_F(HostileInput, TabSeparatorIsNamed) {
  std::string text = ReadData();
  std::replace(text.begin(), text.end(), ',', '\t');
  WriteData(text);
  ExpectRejected("data\\.csv:1: the header is separated by tabs, not ','");
  EditConfig("    file: data.csv\n", "    file: data.csv\n    separator: \"\\t\"\n");
  const Outcome outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
}

// --- The output folder ----------------------------------------------------------------------

TEST_F(HostileInput, OutIsAFile) {
  std::ofstream(dir_ / "out") << "not a folder\n";
  ExpectRejected("out: --out names a file, not a folder", "", dir_ / "out");
}

TEST_F(HostileInput, OutCannotBeCreated) {
  ExpectRejected("/proc/vesselid_out: cannot create the output folder", "", "/proc/vesselid_out");
}

TEST_F(HostileInput, OutIsReadOnly) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
  fs::create_directory(dir_ / "out");
  fs::permissions(dir_ / "out", fs::perms::owner_read | fs::perms::owner_exec);
  ExpectRejected("out: cannot write into the output folder: Permission denied");
  fs::permissions(dir_ / "out", fs::perms::owner_all);
}

TEST_F(HostileInput, OutputNeverReplacesAnInput) {
  fs::rename(dir_ / "data.csv", dir_ / "results.json");
  EditConfig("file: data.csv", "file: results.json");
  const std::string before = ReadFile(dir_ / "results.json");
  const Outcome outcome = Run("", dir_);
  EXPECT_NE(outcome.status, 0);
  EXPECT_TRUE(std::regex_search(
      outcome.output, std::regex("results\\.json: this input is where the output .*results\\.json "
                                 "would be written; choose another --out")))
      << outcome.output;
  EXPECT_EQ(ReadFile(dir_ / "results.json"), before);
}

TEST_F(HostileInput, SecondRunIntoALockedFolderNamesTheFirst) {
  fs::create_directory(dir_ / "out");
  const int fd = ::open((dir_ / "out" / ".vesselid.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  ASSERT_EQ(::write(fd, "4242\n", 5), 5);
  ExpectRejected("out: another vesselid process \\(pid 4242\\) is writing into this folder");
  ::close(fd);
  // Released (as when the first process ends, however it ends): the next run goes ahead.
  const Outcome outcome = Run();
  EXPECT_EQ(outcome.status, 0) << outcome.output;
  EXPECT_FALSE(fs::exists(dir_ / "out" / ".vesselid.lock"));
}

TEST_F(HostileInput, TwoRunsAtOnceIntoOneFolder) {
  // Both started together: exactly one writes the results, the other is refused cleanly
  // (or, if the first finished before the second began, both succeed).
  const std::string command = std::string(VESSELID_BINARY) + " run " +
                              (dir_ / "config.yaml").string() + " --out " +
                              (dir_ / "out").string() + " --quiet > /dev/null 2>&1";
  const std::string both = "(" + command + "; echo $? > " + (dir_ / "a").string() + ") & (" +
                           command + "; echo $? > " + (dir_ / "b").string() + "); wait";
  ASSERT_EQ(std::system(both.c_str()), 0);
  auto status = [&](const char* name) {
    int value = -1;
    std::ifstream(dir_ / name) >> value;
    return value;
  };
  EXPECT_TRUE(status("a") == 0 || status("b") == 0);
  EXPECT_TRUE(status("a") <= 1 && status("b") <= 1);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "results.json"));
}

TEST_F(HostileInput, FullDiskIsFoundBeforeTheRun) {
  // A 64 KiB file system, where the machine lets the test mount one (root with the right).
  const fs::path tiny = dir_ / "tiny";
  fs::create_directory(tiny);
  const std::string mount = "mount -t tmpfs -o size=64k tmpfs " + tiny.string() + " 2>/dev/null";
  if (std::system(mount.c_str()) != 0) GTEST_SKIP() << "cannot mount a small tmpfs here";
  ExpectRejected("out: only [0-9.]+ KiB free on its file system, less than 16 MiB for the results",
                 "", tiny / "out");
  EXPECT_FALSE(fs::exists(tiny / "out"));  // the refused run leaves no folder it made
  EXPECT_EQ(std::system(("umount " + tiny.string()).c_str()), 0);
}

TEST_F(HostileInput, FileSizeLimitIsFoundBeforeTheRun) {
  ExpectRejected("out: the file size limit \\(ulimit -f\\) of .* is less than 16 MiB",
                 "ulimit -f 1024; ");
}

// A write that fails part-way (here a file-size limit, as a full disk would) reports it and
// leaves neither the file nor its temporary.
TEST_F(HostileInput, FailedWriteLeavesNoTemporaryFile) {
  struct rlimit old_limit;
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old_limit), 0);
  auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old_limit;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string error;
  const bool written =
      WriteFileAtomically((dir_ / "big.json").string(), std::string(1 << 20, 'x'), &error);
  Trajectory data;
  data.t.assign(20000, 0.0);
  for (size_t k = 0; k < data.t.size(); ++k) data.t[k] = 0.1 * k;
  data.names = {"a"};
  data.columns = {data.t};
  std::string csv_error;
  const bool csv_written = WriteTrajectoryCsv((dir_ / "big.csv").string(), data, &csv_error);
  ::setrlimit(RLIMIT_FSIZE, &old_limit);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_FALSE(written);
  EXPECT_NE(error.find("big.json: write failed"), std::string::npos) << error;
  EXPECT_FALSE(csv_written);
  EXPECT_NE(csv_error.find("big.csv: write failed"), std::string::npos) << csv_error;
  for (const char* name : {"big.json", "big.json.tmp", "big.csv", "big.csv.tmp"}) {
    EXPECT_FALSE(fs::exists(dir_ / name)) << name;
  }
}

}  // namespace hostile_input_test
}  // namespace vesselid

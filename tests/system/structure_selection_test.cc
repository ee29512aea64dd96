// `vesselid select` end to end: candidate structures cross-validated over whole runs, the
// choice by the one-standard-error rule, then the chosen candidate run, the selection shown in
// results.json, report.txt and report.html.
//
//   StructureSelection: the tanker campaign (configs/nomoto_tanker.yaml) with Norrbin's
//     n1-form against its first-order form, 4-fold by run: the same selection for 1, 2 and
//     every thread; bad select sections refused naming file, line and key.
//   MmgKvlcc2Selection (long): the KVLCC2 campaign (configs/mmg_kvlcc2.yaml): the MMG model
//     against the Nomoto ladder, 3-fold by run on the heading.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "gtest/gtest.h"
#include "nlohmann/json.hpp"

namespace vesselid {
namespace structure_selection_test {

using nlohmann::json;
namespace fs = std::filesystem;

std::string ReadText(const fs::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The tanker config without its own select section (the tests give theirs).
std::string TankerConfig() {
  const std::string text =
      ReadText(std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_tanker.yaml");
  return text.substr(0, text.find("\nselect:")) + "\n";
}

int Command(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

const char kTankerCandidates[] = R"(
select:
  experiments: training
  folds: 4
  candidates:
    - name: norrbin_n1
    - name: first_order_n1
      model: {family: nomoto, type: first_order_n1, length: 320}
      stages:
        - name: output_error
          experiments: training
          free_initial_states: [psi, r]
          parameters:
            T_nd: {start: 2.0, role: fixed}
            K_nd: {start: 1.5, lower: 0.01, upper: 20}
            n1: {start: -0.2, lower: -5, upper: 5}
            delta_0: {start: 0.0, lower: -0.1, upper: 0.1, role: per_experiment}
)";

class StructureSelection : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("vesselid_selection_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    const std::string source = std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_tanker.yaml";
    ASSERT_EQ(Command(std::string(VESSELID_BINARY) + " simulate " + source + " --out " +
                      dir_->string() + " > /dev/null"),
              0);
    std::ofstream(*dir_ / "tanker_select.yaml") << TankerConfig() << kTankerCandidates;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  // Runs `vesselid select` with `threads` into <dir>/<name>; its results.json.
  static json Select(const std::string& name, int threads) {
    const fs::path out = *dir_ / name;
    const std::string command = std::string(VESSELID_BINARY) + " select " +
                                (*dir_ / "tanker_select.yaml").string() + " --data " +
                                dir_->string() + " --out " + out.string() + " --threads " +
                                std::to_string(threads) + " --quiet > /dev/null 2>&1";
    EXPECT_EQ(Command(command), 0) << command;
    std::ifstream in(out / "results.json");
    return json::parse(in, nullptr, false);
  }
  static fs::path* dir_;
};
fs::path* StructureSelection::dir_ = nullptr;

TEST_F(StructureSelection, SameSelectionForAnyThreadCountAndShownEverywhere) {
  json one = Select("one", 1), two = Select("two", 2), all = Select("all", 0);
  ASSERT_TRUE(one.contains("selection"));
  for (json* j : {&one, &two, &all}) (*j)["selection"].erase("time_seconds");
  EXPECT_EQ(one["selection"], two["selection"]);
  EXPECT_EQ(one["selection"], all["selection"]);
  const json& s = one["selection"];
  EXPECT_EQ(s["method"], "4-fold by run");
  EXPECT_EQ(s["folds"].size(), 4u);
  EXPECT_EQ(s["outputs"], json::array({"psi"}));
  ASSERT_EQ(s["candidates"].size(), 2u);
  for (const json& c : s["candidates"]) {
    EXPECT_TRUE(c["usable"].get<bool>()) << c["message"];
    EXPECT_EQ(c["fold_scores"].size(), 4u);
    EXPECT_TRUE(c["score"].is_number()) << c["name"];
    EXPECT_EQ(c["per_run_values"].get<int>(), 8);  // a bias per training run
  }
  EXPECT_EQ(s["candidates"][0]["shared_parameters"].get<int>(), 3);  // K_nd, n1, n3_nd
  EXPECT_EQ(s["candidates"][1]["shared_parameters"].get<int>(), 2);  // K_nd, n1
  ASSERT_TRUE(s["chosen"].is_string());
  // The folds predict each held-out run from its measured start (bias and yaw rate on a
  // burn-in): the tanker's own structure predicts them, the first-order form of a
  // course-unstable ship does not.
  const std::string chosen = s["chosen"];
  EXPECT_EQ(chosen, "norrbin_n1");
  EXPECT_GT(s["candidates"][0]["score"].get<double>(), 50.0);
  EXPECT_GT(s["candidates"][0]["score"].get<double>(), s["candidates"][1]["score"].get<double>());
  // The chosen candidate's run is the one written: its model is the chosen one's.
  for (const json& c : s["candidates"]) {
    if (c["name"] == chosen) {
      EXPECT_EQ(one["model"]["name"], c["model"]);
    }
  }
  const std::string text = ReadText(*dir_ / "one" / "report.txt");
  EXPECT_NE(text.find("structure selection, 4-fold by run"), std::string::npos);
  EXPECT_NE(text.find("<- chosen"), std::string::npos);
  EXPECT_NE(ReadText(*dir_ / "one" / "report.html").find("<h2>Structure selection</h2>"),
            std::string::npos);
}

TEST_F(StructureSelection, BadSelectSectionsAreRefusedNamingFileLineAndKey) {
  const std::string source = TankerConfig();
  const struct {
    const char* section;
    const char* expected;
  } cases[] = {
      {"select:\n  candidates:\n    - {name: a}\n", "select.candidates: needs at least two"},
      {"select:\n  folds: 1\n  candidates: [{name: a}, {name: b}]\n", "select.folds"},
      {"select:\n  candidates: [{name: a}, {name: b, stagez: []}]\n",
       "select.candidates[1].stagez: unknown key"},
      {"select:\n  experiments: nowhere\n  candidates: [{name: a}, {name: b}]\n",
       "'nowhere' is neither an experiment nor a set"},
  };
  for (const auto& c : cases) {
    const fs::path config = *dir_ / "bad.yaml";
    std::ofstream(config) << source << c.section;
    const fs::path log = *dir_ / "bad.log";
    EXPECT_NE(Command(std::string(VESSELID_BINARY) + " select " + config.string() + " --data " +
                      dir_->string() + " --out " + (*dir_ / "bad").string() + " > " + log.string() +
                      " 2>&1"),
              0)
        << c.section;
    const std::string message = ReadText(log);
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_NE(message.find("bad.yaml:"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(*dir_ / "bad" / "results.json"));
  }
}

// The KVLCC2 campaign: the MMG model chosen, above every Nomoto form.
TEST(MmgKvlcc2Selection, MmgChosenOverEveryNomotoForm) {
  const fs::path dir =
      fs::temp_directory_path() / ("vesselid_kvlcc2_select_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string shipped = std::string(VESSELID_SOURCE_DIR) + "/configs/mmg_kvlcc2.yaml";
  ASSERT_EQ(Command(std::string(VESSELID_BINARY) + " simulate " + shipped + " --out " +
                    dir.string() + " > /dev/null"),
            0);
  // Three folds by run instead of the config's five (leave-one-run-out): 4 cases per
  // candidate, not 6.
  std::string text = ReadText(shipped);
  const std::string loro = "folds: leave_one_run_out";
  text.replace(text.find(loro), loro.size(), "folds: 3");
  const std::string config = (dir / "mmg_kvlcc2_select.yaml").string();
  std::ofstream(config) << text;
  ASSERT_EQ(Command(std::string(VESSELID_BINARY) + " select " + config + " --data " + dir.string() +
                    " --out " + (dir / "select").string() + " > " + (dir / "select.txt").string() +
                    " 2>&1"),
            0)
      << ReadText(dir / "select.txt");
  std::ifstream in(dir / "select" / "results.json");
  const json results = json::parse(in);
  const json& s = results["selection"];
  // The full MMG model is chosen, its score above every Nomoto form's by more than their
  // standard errors (the MMG with a linear hull is scored too, and may fall below them).
  double mmg = -1.0;
  for (const json& c : s["candidates"]) {
    ASSERT_TRUE(c["usable"].get<bool>()) << c["name"] << ": " << c["message"];
    if (c["name"] == "mmg") mmg = c["score"].get<double>();
  }
  EXPECT_EQ(s["chosen"], "mmg");
  for (const json& c : s["candidates"]) {
    if (c["model"] == "mmg") continue;
    EXPECT_GT(mmg, c["score"].get<double>() + c["score_se"].get<double>()) << c["name"];
  }
  EXPECT_EQ(results["model"]["name"], "mmg");
  fs::remove_all(dir);
}

}  // namespace structure_selection_test
}  // namespace vesselid

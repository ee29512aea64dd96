// OutputStaging: a set of outputs appears together or not at all. A failure before the
// publication leaves the previous set; a publication killed at any point is finished by the
// next command (FinishPublication), from the on-disk state a kill leaves.
#include "engine/output/output_staging.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "gtest/gtest.h"

namespace vesselid {
namespace output_staging_test {

namespace fs = std::filesystem;

class OutputStagingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One folder per case: ctest runs the cases as processes side by side.
    out_ = fs::temp_directory_path() /
           ("vesselid_output_staging_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(out_);
    fs::create_directories(out_);
  }
  void TearDown() override { fs::remove_all(out_); }

  static void Write(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
  }
  static std::string Read(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  // Stages the set of generation `tag`: results.json, report.txt, traces/<traces...>.
  std::unique_ptr<OutputStaging> Stage(const std::string& tag,
                                       const std::vector<std::string>& traces, bool report_html) {
    std::string error;
    auto staging = OutputStaging::Begin(out_.string(), "run", Known(), &error);
    EXPECT_NE(staging, nullptr) << error;
    if (staging == nullptr) return nullptr;
    const fs::path folder = staging->folder();
    Write(folder / "results.json", tag);
    Write(folder / "report.txt", tag);
    if (report_html) Write(folder / "report.html", tag);
    for (const std::string& t : traces) Write(folder / "traces" / t, tag);
    return staging;
  }
  static std::vector<std::string> Known() {
    return {"results.json", "report.txt", "report.html", "traces", "surfaces"};
  }
  // Every file under --out but the bookkeeping ones, with its content.
  std::map<std::string, std::string> Set() const {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(out_)) {
      const std::string relative = entry.path().lexically_relative(out_).string();
      if (!entry.is_regular_file() || relative.rfind(".vesselid", 0) == 0) continue;
      files[relative] = Read(entry.path());
    }
    return files;
  }

  fs::path out_;
};

TEST_F(OutputStagingTest, PublishedSetReplacesThePreviousOneWhole) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv", "fit.b.csv"}, true)->Publish("results.json", &error))
      << error;
  EXPECT_EQ(Set(), (std::map<std::string, std::string>{{"results.json", "A"},
                                                       {"report.txt", "A"},
                                                       {"report.html", "A"},
                                                       {"traces/fit.a.csv", "A"},
                                                       {"traces/fit.b.csv", "A"}}));
  // The second set has one trace and no report.html: nothing of the first stays.
  ASSERT_TRUE(Stage("B", {"fit.a.csv"}, false)->Publish("results.json", &error)) << error;
  EXPECT_EQ(Set(), (std::map<std::string, std::string>{
                       {"results.json", "B"}, {"report.txt", "B"}, {"traces/fit.a.csv", "B"}}));
  EXPECT_FALSE(fs::exists(out_ / kStagingFolder));
}

TEST_F(OutputStagingTest, EntriesOfThePreviousManifestLeaveWithIt) {
  std::string error;
  auto first = Stage("A", {}, false);
  Write(fs::path(first->folder()) / "sr.lasso_d.csv", "A");  // a step-regression table
  ASSERT_TRUE(first->Publish("results.json", &error)) << error;
  Write(out_ / "notes.txt", "mine");  // the user's, in no manifest
  ASSERT_TRUE(Stage("B", {}, false)->Publish("results.json", &error)) << error;
  EXPECT_FALSE(fs::exists(out_ / "sr.lasso_d.csv"));
  EXPECT_EQ(Read(out_ / "notes.txt"), "mine");
}

TEST_F(OutputStagingTest, UnpublishedStagingLeavesThePreviousSet) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  const auto before = Set();
  Stage("B", {"fit.b.csv"}, false).reset();  // a write failed: never published
  EXPECT_EQ(Set(), before);
  EXPECT_FALSE(fs::exists(out_ / kStagingFolder));
}

TEST_F(OutputStagingTest, AFolderWhereAFileGoesIsRefusedBeforeAnythingChanges) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  fs::remove(out_ / "report.txt");
  Write(out_ / "report.txt" / "inside", "mine");
  const auto before = Set();
  EXPECT_FALSE(Stage("B", {"fit.b.csv"}, true)->Publish("results.json", &error));
  EXPECT_NE(error.find("report.txt: is a folder where vesselid writes a file"), std::string::npos)
      << error;
  EXPECT_EQ(Set(), before);
  EXPECT_FALSE(fs::exists(out_ / kStagingFolder));
}

TEST_F(OutputStagingTest, StagingWithoutJournalIsRemovedByTheNextCommand) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, false)->Publish("results.json", &error)) << error;
  const auto before = Set();
  // A process killed while writing leaves its staging folder without a journal.
  Write(out_ / kStagingFolder / "results.json", "B");
  Write(out_ / kStagingFolder / "traces" / "fit.b.csv", "B");
  bool finished = true;
  ASSERT_TRUE(FinishPublication(out_.string(), &error, &finished)) << error;
  EXPECT_FALSE(finished);
  EXPECT_EQ(Set(), before);
  EXPECT_FALSE(fs::exists(out_ / kStagingFolder));
}

// A publication killed after k of its steps: the journal and the entries not yet moved are in
// the staging folder, the rest in --out. Every k ends, after FinishPublication, in set B.
TEST_F(OutputStagingTest, PublicationKilledAtAnyStepIsFinishedByTheNextCommand) {
  const std::map<std::string, std::string> b = {
      {"results.json", "B"}, {"report.txt", "B"}, {"traces/fit.b.csv", "B"}};
  for (int moved = 0; moved <= 4; ++moved) {
    SCOPED_TRACE(moved);
    fs::remove_all(out_);
    fs::create_directories(out_);
    std::string error;
    ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
    const fs::path staging = out_ / kStagingFolder;
    Write(staging / "results.json", "B");
    Write(staging / "report.txt", "B");
    Write(staging / "traces" / "fit.b.csv", "B");
    Write(staging / ".publish",
          "set run\nlast results.json\nremove report.html\n"
          "entry report.txt\nentry results.json\nentry traces\n");
    // The steps in the order Publish takes them.
    if (moved >= 1) fs::remove(out_ / "results.json");
    if (moved >= 2) fs::remove(out_ / "report.html");
    if (moved >= 3) fs::rename(staging / "report.txt", out_ / "report.txt");
    if (moved >= 4) {
      fs::remove_all(out_ / "traces");
      fs::rename(staging / "traces", out_ / "traces");
    }
    bool finished = false;
    ASSERT_TRUE(FinishPublication(out_.string(), &error, &finished)) << error;
    EXPECT_TRUE(finished);
    EXPECT_EQ(Set(), b);
    EXPECT_FALSE(fs::exists(staging));
  }
}

TEST_F(OutputStagingTest, SetsOfTwoCommandsKeepEachOther) {
  std::string error;
  ASSERT_TRUE(Stage("A", {}, false)->Publish("results.json", &error)) << error;
  auto study = OutputStaging::Begin(out_.string(), "study", {"study.txt", "study.json"}, &error);
  ASSERT_NE(study, nullptr) << error;
  Write(fs::path(study->folder()) / "study.json", "S");
  ASSERT_TRUE(study->Publish("study.json", &error)) << error;
  ASSERT_TRUE(Stage("B", {}, false)->Publish("results.json", &error)) << error;
  EXPECT_EQ(Read(out_ / "study.json"), "S");
  EXPECT_EQ(Read(out_ / "results.json"), "B");
}

}  // namespace output_staging_test
}  // namespace vesselid

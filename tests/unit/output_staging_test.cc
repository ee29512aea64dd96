// OutputStaging: a set of outputs appears together or not at all. A failure before the
// publication leaves the previous set; a publication killed at any point is finished by the
// next command (FinishPublication), from the on-disk state a kill leaves. Nothing a manifest
// does not name is replaced or removed, whatever a journal or a link says.
#include "engine/output/output_staging.h"

#include <sys/stat.h>
#include <sys/xattr.h>
#include <unistd.h>

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
    auto staging = OutputStaging::Begin(out_.string(), "run", &error);
    EXPECT_NE(staging, nullptr) << error;
    if (staging == nullptr) return nullptr;
    const fs::path folder = staging->folder();
    Write(folder / "results.json", tag);
    Write(folder / "report.txt", tag);
    if (report_html) Write(folder / "report.html", tag);
    for (const std::string& t : traces) Write(folder / "traces" / t, tag);
    return staging;
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

  // The folder's inode: a new one once the publication exchanged the whole folder.
  ino_t FolderInode() const {
    struct stat info {};
    ::stat(out_.c_str(), &info);
    return info.st_ino;
  }
  fs::path Sibling() const { return out_.parent_path() / ("." + out_.filename().string() + ".vesselid-swap"); }

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
  EXPECT_NE(error.find("report.txt/inside: vesselid would replace this"), std::string::npos)
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
  for (int moved = 0; moved <= 6; ++moved) {
    SCOPED_TRACE(moved);
    fs::remove_all(out_);
    fs::create_directories(out_);
    std::string error;
    ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
    const fs::path staging = out_ / kStagingFolder;
    Write(staging / "results.json", "B");
    Write(staging / "report.txt", "B");
    Write(staging / "traces" / "fit.b.csv", "B");
    Write(staging / kJournal,
          "set run\nlast results.json\nremove report.html\n"
          "entry report.txt\nentry results.json\nentry traces\n");
    // The steps in the order Publish takes them.
    if (moved >= 1) fs::remove(out_ / "results.json");
    if (moved >= 2) fs::remove(out_ / "report.html");
    if (moved >= 3) fs::remove(out_ / "report.txt");
    if (moved >= 4) fs::remove_all(out_ / "traces");
    if (moved >= 5) fs::rename(staging / "report.txt", out_ / "report.txt");
    if (moved >= 6) fs::rename(staging / "traces", out_ / "traces");
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
  auto study = OutputStaging::Begin(out_.string(), "study", &error);
  ASSERT_NE(study, nullptr) << error;
  Write(fs::path(study->folder()) / "study.json", "S");
  ASSERT_TRUE(study->Publish("study.json", &error)) << error;
  ASSERT_TRUE(Stage("B", {}, false)->Publish("results.json", &error)) << error;
  EXPECT_EQ(Read(out_ / "study.json"), "S");
  EXPECT_EQ(Read(out_ / "results.json"), "B");
}

// A user's entries where a run writes its own (the config's folder as --out, with the user's
// traces/ and report.txt): refused before anything changes, every byte kept.
TEST_F(OutputStagingTest, AUsersEntryInTheWayIsRefusedAndKept) {
  Write(out_ / "traces" / "gps_2026.csv", "mine");
  Write(out_ / "surfaces" / "hull.stl", "hull");
  std::string error;
  EXPECT_FALSE(Stage("A", {"fit.a.csv"}, false)->Publish("results.json", &error));
  EXPECT_NE(error.find("did not write it"), std::string::npos) << error;
  EXPECT_NE(error.find("traces"), std::string::npos) << error;
  EXPECT_EQ(Read(out_ / "traces" / "gps_2026.csv"), "mine");
  EXPECT_EQ(Read(out_ / "surfaces" / "hull.stl"), "hull");
  EXPECT_FALSE(fs::exists(out_ / "results.json"));
  EXPECT_FALSE(fs::exists(out_ / kStagingFolder));

  fs::remove_all(out_ / "traces");
  Write(out_ / "report.txt", "my own report");
  EXPECT_FALSE(Stage("A", {}, false)->Publish("results.json", &error));
  EXPECT_EQ(Read(out_ / "report.txt"), "my own report");
}

TEST_F(OutputStagingTest, AFileAddedInsideAnOutputFolderIsNotReplaced) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, false)->Publish("results.json", &error)) << error;
  Write(out_ / "traces" / "my_notes.txt", "mine");
  EXPECT_FALSE(Stage("B", {"fit.b.csv"}, false)->Publish("results.json", &error));
  EXPECT_NE(error.find("my_notes.txt"), std::string::npos) << error;
  EXPECT_EQ(Read(out_ / "traces" / "my_notes.txt"), "mine");
  EXPECT_EQ(Read(out_ / "results.json"), "A");
}

// A staging folder that is a link (to a forged journal and a file outside --out): neither
// read nor followed; the link goes, the file outside stays where it is.
TEST_F(OutputStagingTest, AStagingLinkIsNotFollowed) {
  const fs::path outside = out_.string() + "_outside";
  fs::remove_all(outside);
  Write(outside / "precious.csv", "outside");
  Write(outside / kJournal, "set run\nlast precious.csv\nentry precious.csv\n");
  fs::create_directory_symlink(outside, out_ / kStagingFolder);
  std::string error;
  ASSERT_TRUE(FinishPublication(out_.string(), &error)) << error;
  EXPECT_FALSE(fs::exists(fs::symlink_status(out_ / kStagingFolder)));
  EXPECT_EQ(Read(outside / "precious.csv"), "outside");
  EXPECT_FALSE(fs::exists(out_ / "precious.csv"));
  fs::remove_all(outside);
}

// A journal asking to remove or replace what no manifest names is not carried out.
TEST_F(OutputStagingTest, AForgedJournalCannotRemoveAUsersFile) {
  std::string error;
  ASSERT_TRUE(Stage("A", {}, false)->Publish("results.json", &error)) << error;
  Write(out_ / "notes.txt", "mine");
  Write(out_ / kStagingFolder / "results.json", "B");
  Write(out_ / kStagingFolder / kJournal,
        "set run\nlast results.json\nremove notes.txt\nentry results.json\n");
  EXPECT_FALSE(FinishPublication(out_.string(), &error));
  EXPECT_NE(error.find("notes.txt"), std::string::npos) << error;
  EXPECT_EQ(Read(out_ / "notes.txt"), "mine");
  EXPECT_EQ(Read(out_ / "results.json"), "A");
}

// A manifest reached through a link is not vesselid's: what it names stays the user's.
TEST_F(OutputStagingTest, AManifestThatIsALinkIsNotTrusted) {
  const fs::path forged = out_.string() + "_manifest";
  Write(forged, "report.txt\n");
  fs::create_symlink(forged, out_ / ".vesselid-run.set");
  Write(out_ / "report.txt", "my own report");
  std::string error;
  EXPECT_FALSE(Stage("A", {}, false)->Publish("results.json", &error));
  EXPECT_EQ(Read(out_ / "report.txt"), "my own report");
  EXPECT_TRUE(OwnedEntries(out_.string()).empty());
  fs::remove(forged);
}

// A folder of vesselid's outputs only is exchanged whole (a new folder at its path, so a
// reader sees the earlier set or the new one, never a mixture and never neither), carrying
// the marker and the lock (the same files: the lock held stays held); no sibling, token or
// journal is left.
TEST_F(OutputStagingTest, AFolderOfVesselidsOutputsOnlyIsExchangedWhole) {
  std::string error;
  Write(out_ / kMarkerFile, "marker");
  Write(out_ / kLockFile, "123\n");
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  const ino_t before = FolderInode();
  struct stat lock_before {};
  ::stat((out_ / kLockFile).c_str(), &lock_before);
  ASSERT_TRUE(Stage("B", {"fit.b.csv"}, false)->Publish("results.json", &error)) << error;
  EXPECT_NE(FolderInode(), before);
  EXPECT_EQ(Set(), (std::map<std::string, std::string>{
                       {"results.json", "B"}, {"report.txt", "B"}, {"traces/fit.b.csv", "B"}}));
  struct stat lock_after {};
  ASSERT_EQ(::stat((out_ / kLockFile).c_str(), &lock_after), 0);
  EXPECT_EQ(lock_after.st_ino, lock_before.st_ino);
  EXPECT_EQ(Read(out_ / kMarkerFile), "marker");
  EXPECT_FALSE(fs::exists(Sibling()));
  EXPECT_FALSE(fs::exists(out_ / kSwapToken));
  EXPECT_FALSE(fs::exists(out_ / kJournal));
  EXPECT_FALSE(fs::exists(out_ / kStagingFolder));
  // The new folder's manifest names the new set: a third set replaces it whole again.
  ASSERT_TRUE(Stage("C", {"fit.a.csv"}, false)->Publish("results.json", &error)) << error;
  EXPECT_EQ(Set(), (std::map<std::string, std::string>{
                       {"results.json", "C"}, {"report.txt", "C"}, {"traces/fit.a.csv", "C"}}));
}

// A user's file beside the outputs would be left behind by an exchange: the set is published
// entry by entry into the same folder, and the file is kept.
TEST_F(OutputStagingTest, AUsersFileBesideTheOutputsKeepsTheFolder) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  Write(out_ / "notes.txt", "mine");
  const ino_t before = FolderInode();
  ASSERT_TRUE(Stage("B", {"fit.b.csv"}, false)->Publish("results.json", &error)) << error;
  EXPECT_EQ(FolderInode(), before);
  EXPECT_EQ(Set(), (std::map<std::string, std::string>{{"notes.txt", "mine"},
                                                       {"results.json", "B"},
                                                       {"report.txt", "B"},
                                                       {"traces/fit.b.csv", "B"}}));
}

// A process working inside the folder (a shell at its prompt there) would be left in a removed
// folder: no exchange while one does.
TEST_F(OutputStagingTest, AProcessWorkingInsideKeepsTheFolder) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  const fs::path was = fs::current_path();
  fs::create_directories(out_ / "traces");
  fs::current_path(out_ / "traces");
  const ino_t before = FolderInode();
  const bool published = Stage("B", {"fit.a.csv"}, false)->Publish("results.json", &error);
  fs::current_path(was);
  ASSERT_TRUE(published) << error;
  EXPECT_EQ(FolderInode(), before);
  EXPECT_EQ(Read(out_ / "results.json"), "B");
}

// An entry at the sibling's name that is not vesselid's (no token naming this folder) is the
// user's: left as it is, and the set published entry by entry.
TEST_F(OutputStagingTest, AUsersEntryAtTheSiblingsNameIsKept) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  Write(Sibling() / "mine.txt", "mine");
  Write(Sibling() / kSwapToken, "old\n/somewhere/else\n");
  const ino_t before = FolderInode();
  ASSERT_TRUE(Stage("B", {"fit.a.csv"}, false)->Publish("results.json", &error)) << error;
  EXPECT_EQ(FolderInode(), before);
  EXPECT_EQ(Read(out_ / "results.json"), "B");
  EXPECT_EQ(Read(Sibling() / "mine.txt"), "mine");
  fs::remove_all(Sibling());
}

// The exchanged folder keeps --out's permission bits (a folder made private stays private).
TEST_F(OutputStagingTest, TheExchangedFolderKeepsItsPermissions) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  fs::permissions(out_, fs::perms::owner_all);
  const ino_t before = FolderInode();
  ASSERT_TRUE(Stage("B", {"fit.a.csv"}, false)->Publish("results.json", &error)) << error;
  EXPECT_NE(FolderInode(), before);
  EXPECT_EQ(fs::status(out_).permissions() & fs::perms::all, fs::perms::owner_all);
}

// The exchanged folder keeps --out's extended attributes (a user's note; ACLs alike).
TEST_F(OutputStagingTest, TheExchangedFolderKeepsItsExtendedAttributes) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  const std::string note = "field campaign 7";
  if (::setxattr(out_.c_str(), "user.note", note.data(), note.size(), 0) != 0) {
    GTEST_SKIP() << "no user extended attributes on this file system";
  }
  const ino_t before = FolderInode();
  ASSERT_TRUE(Stage("B", {"fit.a.csv"}, false)->Publish("results.json", &error)) << error;
  EXPECT_NE(FolderInode(), before);
  char value[64] = {0};
  ASSERT_EQ(::getxattr(out_.c_str(), "user.note", value, sizeof(value)),
            static_cast<ssize_t>(note.size()));
  EXPECT_EQ(std::string(value), note);
}

// A file of the user's at a reserved name that vesselid cannot tell it wrote (a token naming
// no folder, a temporary) keeps the folder from being exchanged, and is kept.
TEST_F(OutputStagingTest, AUsersFileAtAReservedNameIsNotExchangedAway) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  Write(out_ / kSwapToken, "my notes");
  const ino_t before = FolderInode();
  ASSERT_TRUE(Stage("B", {"fit.a.csv"}, false)->Publish("results.json", &error)) << error;
  EXPECT_EQ(FolderInode(), before);
  EXPECT_EQ(Read(out_ / kSwapToken), "my notes");
  EXPECT_EQ(Read(out_ / "results.json"), "B");
}

// A folder at the sibling's name with a token naming this folder, but holding the user's
// files: only what vesselid's manifests there name is removed, and the user's files stay
// (with the folder); a "new" one without its journal is left alone.
TEST_F(OutputStagingTest, AUsersFilesInAForgedSiblingAreKept) {
  std::string error;
  ASSERT_TRUE(Stage("A", {"fit.a.csv"}, true)->Publish("results.json", &error)) << error;
  const std::string canonical = fs::canonical(out_).string();
  for (const char* side : {"old", "new"}) {
    SCOPED_TRACE(side);
    Write(Sibling() / "thesis.tex", "thesis");
    Write(Sibling() / "photos" / "a.jpg", "photo");
    Write(Sibling() / kSwapToken, std::string(side) + "\n" + canonical + "\n");
    ASSERT_TRUE(Stage("B", {"fit.a.csv"}, false)->Publish("results.json", &error)) << error;
    EXPECT_EQ(Read(Sibling() / "thesis.tex"), "thesis");
    EXPECT_EQ(Read(Sibling() / "photos" / "a.jpg"), "photo");
    EXPECT_EQ(Read(out_ / "results.json"), "B");
    fs::remove_all(Sibling());
  }
}

// What a kill after the exchange leaves (the earlier folder at the sibling's name, the journal
// and token in the new one) is finished by the next command, also for a folder whose name holds
// a newline; an empty sibling (killed after its token went) is removed.
TEST_F(OutputStagingTest, AKillAfterTheExchangeIsFinishedWhateverTheFoldersName) {
  const fs::path odd = out_ / "o\nx";
  fs::create_directories(odd);
  const fs::path sibling = out_ / ".o\nx.vesselid-swap";
  const std::string canonical = fs::canonical(odd).string();
  Write(odd / kSwapToken, "new\n" + canonical + "\n");
  Write(odd / kJournal, "set run\nlast results.json\nentry results.json\n");
  Write(odd / "results.json", "B");
  Write(sibling / kSwapToken, "old\n" + canonical + "\n");
  Write(sibling / kMarkerFile, "marker");
  std::string error;
  ASSERT_TRUE(FinishPublication(odd.string(), &error)) << error;
  EXPECT_FALSE(fs::exists(sibling));
  EXPECT_FALSE(fs::exists(odd / kSwapToken));
  EXPECT_FALSE(fs::exists(odd / kJournal));
  EXPECT_EQ(Read(odd / "results.json"), "B");
  fs::create_directories(sibling);
  ASSERT_TRUE(FinishPublication(odd.string(), &error)) << error;
  EXPECT_FALSE(fs::exists(sibling));
}

}  // namespace output_staging_test
}  // namespace vesselid

// TrajectoryCache: experiments that read one file alike share one record (windows of a log),
// the reading's findings come once, and an edited copy edits a shared record once.
#include "engine/run/trajectory_cache.h"

#include <filesystem>
#include <fstream>

#include "engine/base/memory_budget.h"
#include "gtest/gtest.h"

namespace vesselid {
namespace trajectory_cache_test {

namespace fs = std::filesystem;

class TrajectoryCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // One file per case: ctest runs the cases as processes side by side.
    file_ =
        (fs::temp_directory_path() /
         ("vesselid_trajectory_cache_" +
          std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".csv"))
            .string();
    std::ofstream out(file_);
    out << "t,delta,psi,notes\n";
    for (int k = 0; k < 100; ++k) out << k * 0.1 << "," << 0.01 * k << "," << 0.02 * k << ",x\n";
  }
  void TearDown() override { fs::remove(file_); }
  ExperimentSpec Window(const std::string& name, double begin, double end) const {
    ExperimentSpec spec;
    spec.name = name;
    spec.file = file_;
    spec.inputs = {{"delta", "delta"}};
    spec.outputs = {{"psi", "psi"}};
    spec.t_begin = begin;
    spec.t_end = end;
    return spec;
  }
  std::string file_;
};

TEST_F(TrajectoryCacheTest, WindowsOfOneFileShareItsRecord) {
  TrajectoryCache cache;
  std::string error;
  const Trajectory* a = cache.Load(Window("a", 0.0, 5.0), &error);
  const Trajectory* b = cache.Load(Window("b", 5.0, 9.9), &error);
  ASSERT_NE(a, nullptr) << error;
  EXPECT_EQ(a, b);
  EXPECT_EQ(cache.Find("b"), a);
  EXPECT_EQ(cache.Find("c"), nullptr);
  // Other columns read (or in degrees) make another record.
  ExperimentSpec degrees = Window("c", 0.0, 5.0);
  degrees.degree_columns = {"psi"};
  const Trajectory* c = cache.Load(degrees, &error);
  ASSERT_NE(c, nullptr) << error;
  EXPECT_NE(c, a);
  EXPECT_NEAR(c->columns[c->Find("psi")][10], a->columns[a->Find("psi")][10] * M_PI / 180, 1e-15);
}

TEST_F(TrajectoryCacheTest, ReadingFindingsComeOnceNotesPerExperiment) {
  TrajectoryCache cache;
  std::string error;
  ASSERT_NE(cache.Load(Window("a", 0.0, 5.0), &error), nullptr) << error;
  ASSERT_NE(cache.Load(Window("b", 5.0, 9.9), &error), nullptr) << error;
  Finding note = MakeFinding(FindingKind::kSegmentSkipped, "skipped");
  note.experiment = "b";
  cache.AddNote("b", note);
  cache.AddNote("b", note);  // kept once
  const std::vector<Finding> findings = cache.Findings({"a", "b"});
  int unread = 0, skipped = 0;
  for (const Finding& f : findings) {
    unread += f.kind == FindingKind::kColumnsNotRead;
    skipped += f.kind == FindingKind::kSegmentSkipped;
  }
  EXPECT_EQ(unread, 1);  // the 'notes' column, once for the shared file
  EXPECT_EQ(skipped, 1);
}

TEST_F(TrajectoryCacheTest, EditedCopyEditsASharedRecordOnce) {
  TrajectoryCache cache;
  std::string error;
  const Trajectory* original = cache.Load(Window("a", 0.0, 5.0), &error);
  ASSERT_NE(cache.Load(Window("b", 5.0, 9.9), &error), nullptr) << error;
  int edits = 0;
  TrajectoryCache copy = cache.EditedCopy({"a", "b"}, [&](const std::string&, Trajectory* data) {
    ++edits;
    for (double& v : data->columns[data->Find("delta")]) v += 1.0;
  });
  EXPECT_EQ(edits, 1);
  EXPECT_EQ(copy.Find("a"), copy.Find("b"));
  EXPECT_DOUBLE_EQ(copy.Find("a")->columns[0][3], original->columns[0][3] + 1.0);
}

TEST(MemoryBudget, ScopedBudgetRestoresAndFormatsInBinaryUnits) {
  const std::uint64_t before = MemoryBudget();
  {
    const ScopedMemoryBudget budget(std::uint64_t{3} << 20);
    EXPECT_EQ(MemoryBudget(), std::uint64_t{3} << 20);
    EXPECT_EQ(OverBudget("the test's matrices", 1.5 * (1 << 30)),
              "the test's matrices need 1.5 GiB, more than the memory budget of 3 MiB "
              "(limits.memory_mb)");
  }
  EXPECT_EQ(MemoryBudget(), before);
  EXPECT_GE(DefaultMemoryBudget(), std::uint64_t{1} << 30);
  EXPECT_EQ(FormatBytes(812), "812 B");
  EXPECT_EQ(FormatBytes(1536), "1.5 KiB");
}

}  // namespace trajectory_cache_test
}  // namespace vesselid

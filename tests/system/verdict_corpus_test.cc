// The verdict on a labelled corpus (tests/support/verdict_corpus.h): 60 runs of the patrol
// vessel, labelled good or bad by their known truth. No good run may have a failure and at
// most 5 % of them any warning (a false alarm is a defect); every bad run must be doubtful or
// failed (a miss is one too). The confusion matrix is printed.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <thread>

#include "engine/base/parallel_for.h"
#include "gtest/gtest.h"
#include "tests/support/verdict_corpus.h"

namespace vesselid {
namespace verdict_corpus_test {

namespace fs = std::filesystem;

TEST(VerdictCorpus, GoodRunsAreQuietAndBadRunsAreCalledOut) {
  // VESSELID_CORPUS_DIR keeps every case's config, data and nothing else there (to run
  // another build on the same cases).
  const char* keep = std::getenv("VESSELID_CORPUS_DIR");
  const fs::path dir = keep != nullptr ? fs::path(keep)
                                       : fs::temp_directory_path() /
                                             ("vesselid_verdict_corpus_" + std::to_string(getpid()));
  const std::vector<testing::CorpusCase> cases = testing::VerdictCorpus();
  ASSERT_GE(cases.size(), 60u);
  std::vector<testing::CorpusOutcome> outcomes(cases.size());
  std::vector<std::string> errors(cases.size());
  ParallelFor(static_cast<int>(cases.size()), 0, [&](int i) {
    outcomes[i] = testing::RunCorpusCase(cases[i], dir / cases[i].name, &errors[i]);
  });
  if (keep == nullptr) fs::remove_all(dir);
  int matrix[2][3] = {};  // [bad, good][good, doubtful, failed]
  int good = 0, good_warned = 0;
  for (size_t i = 0; i < outcomes.size(); ++i) {
    const testing::CorpusOutcome& o = outcomes[i];
    ASSERT_TRUE(o.ran) << o.name << ": " << errors[i];
    ++matrix[o.good][static_cast<int>(o.verdict)];
    std::string lines;
    for (const Finding& f : o.findings) {
      if (f.severity != FindingSeverity::kInfo) lines += "\n    " + DescribeFinding(f);
    }
    if (o.good) {
      ++good;
      good_warned += o.verdict != Verdict::kGood;
      EXPECT_NE(o.verdict, Verdict::kFailed) << o.name << lines;
    } else {
      EXPECT_NE(o.verdict, Verdict::kGood) << o.name << " (" << o.why << ")" << lines;
    }
    std::printf("%-28s %-4s %-9s %s%s\n", o.name.c_str(), o.good ? "good" : "bad",
                VerdictToString(o.verdict), o.why.c_str(), lines.c_str());
  }
  std::printf("\n              verdict good  doubtful  failed\n");
  std::printf("label good   %12d %9d %7d\n", matrix[1][0], matrix[1][1], matrix[1][2]);
  std::printf("label bad    %12d %9d %7d\n", matrix[0][0], matrix[0][1], matrix[0][2]);
  EXPECT_LE(good_warned, 0.05 * good) << good_warned << " of " << good << " good runs warned";
  // The corpus holds both labels in numbers that make the rates mean something.
  EXPECT_GE(good, 20);
  EXPECT_GE(static_cast<int>(outcomes.size()) - good, 20);
}

}  // namespace verdict_corpus_test
}  // namespace vesselid

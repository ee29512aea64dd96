// The verdict corpus (tests/support/verdict_corpus.h) as a confusion matrix: the run's verdict
// against its label from the truth, then per finding kind at warning or failure severity how
// many good runs and how many bad runs it fired on (a kind firing on good runs is a false
// alarm; the bad runs no kind fires on are misses).
//
//   build/tests/benchmarks/benchmark_verdicts
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "engine/base/parallel_for.h"
#include "glog/logging.h"
#include "tests/support/verdict_corpus.h"

int main(int, char** argv) {
  google::InitGoogleLogging(argv[0]);
  FLAGS_minloglevel = google::GLOG_FATAL;  // the corpus's diverging starts are expected
  namespace fs = std::filesystem;
  using namespace vesselid;
  const fs::path dir =
      fs::temp_directory_path() / ("vesselid_benchmark_verdicts_" + std::to_string(getpid()));
  const std::vector<testing::CorpusCase> cases = testing::VerdictCorpus();
  std::vector<testing::CorpusOutcome> outcomes(cases.size());
  std::vector<std::string> errors(cases.size());
  ParallelFor(static_cast<int>(cases.size()), 0, [&](int i) {
    outcomes[i] = testing::RunCorpusCase(cases[i], dir / cases[i].name, &errors[i]);
  });
  fs::remove_all(dir);
  int matrix[2][3] = {};
  int labelled[2] = {};
  std::map<std::string, std::pair<int, int>> by_kind;  // kind: (good runs, bad runs)
  for (size_t i = 0; i < outcomes.size(); ++i) {
    const testing::CorpusOutcome& o = outcomes[i];
    if (!o.ran) {
      std::fprintf(stderr, "%s: %s\n", o.name.c_str(), errors[i].c_str());
      return 1;
    }
    ++matrix[o.good][static_cast<int>(o.verdict)];
    ++labelled[o.good];
    std::set<std::string> kinds;
    for (const Finding& f : o.findings) {
      if (f.severity != FindingSeverity::kInfo) kinds.insert(FindingKindToString(f.kind));
    }
    for (const std::string& k : kinds) (o.good ? by_kind[k].first : by_kind[k].second)++;
  }
  std::printf("verdict corpus: %zu runs (%d good, %d bad by their truth)\n\n", outcomes.size(),
              labelled[1], labelled[0]);
  std::printf("              verdict good  doubtful  failed\n");
  std::printf("label good   %12d %9d %7d\n", matrix[1][0], matrix[1][1], matrix[1][2]);
  std::printf("label bad    %12d %9d %7d\n\n", matrix[0][0], matrix[0][1], matrix[0][2]);
  std::printf("  %-28s %10s %10s\n", "finding kind (warning+)", "good runs", "bad runs");
  for (const auto& [kind, counts] : by_kind) {
    std::printf("  %-28s %6d/%-3d %6d/%-3d\n", kind.c_str(), counts.first, labelled[1],
                counts.second, labelled[0]);
  }
  return 0;
}

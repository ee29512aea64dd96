// Wall time of a whole `vesselid study` on one and two processes (and on one process with
// two threads), and whether the merged results agree.
//
//   build/tests/benchmarks/benchmark_study [config] [part]
//
// Defaults: configs/nomoto_patrol.yaml, part monte_carlo (200 cases). The config's data are
// simulated first into a temporary folder.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "nlohmann/json.hpp"
#include "tests/support/study_json.h"

namespace {

namespace testing = vesselid::testing;
namespace fs = std::filesystem;
using nlohmann::json;

// Runs the command; its wall time in seconds, or a negative value if it failed.
double Timed(const std::string& command) {
  const auto start = std::chrono::steady_clock::now();
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "failed: %s\n", command.c_str());
    return -1.0;
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

json Load(const fs::path& dir) {
  std::ifstream in(dir / "study.json");
  return json::parse(in, nullptr, false);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string config =
      argc > 1 ? argv[1] : std::string(VESSELID_SOURCE_DIR) + "/configs/nomoto_patrol.yaml";
  const std::string part = argc > 2 ? argv[2] : "monte_carlo";
  const fs::path dir = fs::temp_directory_path() / "vesselid_benchmark_study";
  fs::remove_all(dir);
  const std::string binary = VESSELID_BINARY;
  if (Timed(binary + " simulate " + config + " --out " + dir.string() + " > /dev/null") < 0) {
    return 1;
  }
  auto study = [&](const std::string& launcher, const std::string& out, int threads) {
    return Timed(launcher + binary + " study " + config + " --data " + dir.string() + " --out " +
                 (dir / out).string() + " --only " + part + " --threads " +
                 std::to_string(threads) + " --quiet > /dev/null");
  };
  const double one = study("", "one", 1);
  const double threads = study("", "threads", 2);
  double two = -1.0;
#ifdef VESSELID_MPIEXEC
  two = study("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " +
                  std::string(VESSELID_MPIEXEC) + " -np 2 --oversubscribe ",
              "two", 1);
#endif
  const json reference = Load(dir / "one");
  if (one < 0 || threads < 0 || reference.is_discarded()) return 1;
  const json& section = reference[part];
  const size_t cases = section.contains("cases") ? section["cases"].size() : 0;
  std::printf("study %s of %s: %zu cases\n", part.c_str(), config.c_str(), cases);
  std::printf("  1 process,  1 thread : %8.1f s\n", one);
  std::printf("  1 process,  2 threads: %8.1f s  (x%.2f)  same results: %s\n", threads,
              one / threads,
              testing::ComparableStudy(Load(dir / "threads")) == testing::ComparableStudy(reference) ? "yes" : "NO");
  if (two > 0) {
    std::printf("  2 processes (mpirun) : %8.1f s  (x%.2f)  same results: %s\n", two, one / two,
                testing::ComparableStudy(Load(dir / "two")) == testing::ComparableStudy(reference) ? "yes" : "NO");
  } else {
    std::printf("  2 processes (mpirun) : not built with MPI\n");
  }
  fs::remove_all(dir);
  return 0;
}

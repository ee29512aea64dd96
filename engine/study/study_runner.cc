#include "engine/study/study_runner.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>

#ifdef VESSELID_WITH_MPI
#include <mpi.h>
#endif
#ifdef VESSELID_WITH_OPENMP
#include <omp.h>
#endif
#if defined(__SANITIZE_ADDRESS__)
#define VESSELID_LEAK_CHECKED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(leak_sanitizer)
#define VESSELID_LEAK_CHECKED 1
#endif
#endif
#ifdef VESSELID_LEAK_CHECKED
#include <sanitizer/lsan_interface.h>
#endif

#include "engine/base/parallel_for.h"

namespace vesselid {
namespace {

using nlohmann::json;

const ProcessGroup* current_group = nullptr;

#ifdef VESSELID_WITH_MPI
// Open MPI keeps some of what its calls allocate until exit, partly in plugins it unloads,
// whose frames LeakSanitizer can then neither name nor suppress: not vesselid's leaks, so
// leak checking is off in this thread while one runs (in leak-checked builds).
#ifdef VESSELID_LEAK_CHECKED
using OpenMpiAllocations = __lsan::ScopedDisabler;
#else
struct OpenMpiAllocations {
  OpenMpiAllocations() {}  // user-provided: a guard object, not an unused variable
};
#endif

// Gathers every rank's (index, result) pairs on rank 0 as one JSON text per rank.
std::vector<json> GatherOnRoot(const json& mine) {
  const OpenMpiAllocations unchecked;
  const std::string text = mine.dump();
  int size = 0, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int length = static_cast<int>(text.size());
  std::vector<int> lengths(size), offsets(size);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string all;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) {
      offsets[r] = total;
      total += lengths[r];
    }
    all.resize(total);
  }
  MPI_Gatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR,
              0, MPI_COMM_WORLD);
  std::vector<json> parts;
  if (rank == 0) {
    for (int r = 0; r < size; ++r) parts.push_back(json::parse(all.substr(offsets[r], lengths[r])));
  }
  return parts;
}
#endif

}  // namespace

bool StartedByMpiLauncher() {
  // What the launchers set in every process they start: Open MPI's mpirun (OMPI_*, PMIx),
  // MPICH's and Intel MPI's Hydra (PMI_*), Slurm's srun with PMI-2 or PMIx.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

ProcessGroup::ProcessGroup(int* argc, char*** argv) {
#ifdef VESSELID_WITH_OPENMP
  omp_set_num_threads(1);  // the solves a study runs outside RunCases too
#endif
#ifdef VESSELID_WITH_MPI
  // A program started without a launcher is a group of one, as MPI's singleton start would
  // make it, without the 0.3 s (wall) that Open MPI's start and finish take.
  if (!StartedByMpiLauncher()) {
    current_group = this;
    return;
  }
  const OpenMpiAllocations unchecked;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm local;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &local);
  MPI_Comm_size(local, &local_size_);
  MPI_Comm_free(&local);
  initialised_ = true;
#endif
  current_group = this;
}

ProcessGroup::~ProcessGroup() {
#ifdef VESSELID_WITH_MPI
  const OpenMpiAllocations unchecked;
  if (initialised_) MPI_Finalize();
#endif
  if (current_group == this) current_group = nullptr;
}

const ProcessGroup& ProcessGroup::Current() {
  static const ProcessGroup single;
  return current_group != nullptr ? *current_group : single;
}

bool ProcessGroup::built_with_mpi() {
#ifdef VESSELID_WITH_MPI
  return true;
#else
  return false;
#endif
}

int CaseThreads(const CaseOptions& options) {
  if (options.threads > 0) return options.threads;
  const int cores = std::max(1u, std::thread::hardware_concurrency());
  return std::max(1, cores / std::max(1, ProcessGroup::Current().local_size()));
}

void RunCases(int count, const CaseFunction& run, const CaseOptions& options,
              std::vector<json>* results, const CaseProgress& progress) {
  const ProcessGroup& group = ProcessGroup::Current();
  std::vector<int> mine;
  for (int i = group.rank(); i < count; i += group.size()) mine.push_back(i);
  std::vector<json> done(mine.size());
  std::atomic<size_t> next{0};
  std::mutex progress_mutex;
  auto worker = [&]() {
    const ParallelWorkerScope scope;  // the cases own the cores: their solves take one each
#ifdef VESSELID_WITH_OPENMP
    // One OpenMP thread inside each case (SuiteSparse): sums in a fixed order.
    omp_set_num_threads(1);
#endif
    for (size_t k = next++; k < mine.size(); k = next++) {
      json result;
      try {
        result = run(mine[k]);
      } catch (const std::exception& e) {
        result = {{"usable", false}, {"message", e.what()}};
      }
      if (progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress(mine[k], result);
      }
      done[k] = std::move(result);
    }
  };
  const int threads = std::min<int>(CaseThreads(options), std::max<size_t>(1, mine.size()));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();

  results->clear();
  if (group.size() == 1) {
    *results = std::move(done);
    return;
  }
#ifdef VESSELID_WITH_MPI
  json pairs = json::array();
  for (size_t k = 0; k < mine.size(); ++k) pairs.push_back({mine[k], std::move(done[k])});
  std::vector<json> parts = GatherOnRoot(pairs);
  if (!group.root()) return;
  results->assign(count, json());
  for (json& part : parts) {
    for (json& pair : part) (*results)[pair[0].get<int>()] = std::move(pair[1]);
  }
#endif
}

}  // namespace vesselid

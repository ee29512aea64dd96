// Runs a study's cases over the cores of one machine and, when the engine is built with MPI
// and started under `mpirun -np K`, over K processes.
//
// A case is a pure function of its index: everything random in it is seeded from the study
// seed and the index (CaseSeed), never from a stream shared between cases. Case i runs on
// rank i mod K, on one of that rank's threads; each case's result is a JSON value, gathered
// on rank 0 in index order. The merged results are therefore the same for any K and any
// number of threads.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/base/case_seed.h"
#include "engine/study/case_options.h"
#include "nlohmann/json.hpp"

namespace vesselid {

// The processes of a study: rank and size under MPI, 0 and 1 otherwise.
class ProcessGroup {
 public:
  // Initialises MPI when built with it and started by an MPI launcher (mpirun, mpiexec,
  // srun: StartedByMpiLauncher), and finalises it on destruction; one per program, created
  // before any study runs. Started otherwise, the program is a group of one.
  ProcessGroup(int* argc, char*** argv);
  ~ProcessGroup();
  ProcessGroup(const ProcessGroup&) = delete;
  ProcessGroup& operator=(const ProcessGroup&) = delete;

  // The group of the running program; a single process when none was created.
  static const ProcessGroup& Current();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  // Processes of this group on this machine (for the default thread count).
  int local_size() const { return local_size_; }
  static bool built_with_mpi();

 private:
  ProcessGroup() = default;
  int rank_ = 0;
  int size_ = 1;
  int local_size_ = 1;
  bool initialised_ = false;
};

// Whether an MPI launcher started this process (its environment names a rank).
bool StartedByMpiLauncher();

// CaseSeed (engine/base/case_seed.h): the seed of case `index` of a study part.


using CaseFunction = std::function<nlohmann::json(int index)>;
// Told on the calling rank after each of its cases ends (progress output; serialised).
using CaseProgress = std::function<void(int index, const nlohmann::json& result)>;

// Runs cases [0, count). Every rank must call it with the same count. On rank 0 `results`
// holds every case's result in index order; on other ranks it is left empty. A case that
// throws records {"usable": false, "message": what()}.
void RunCases(int count, const CaseFunction& run, const CaseOptions& options,
              std::vector<nlohmann::json>* results, const CaseProgress& progress = nullptr);

// Worker threads RunCases uses with these options.
int CaseThreads(const CaseOptions& options);

}  // namespace vesselid

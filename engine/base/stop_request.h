// A request to stop the running identification early, made from outside it (the Python
// package's Ctrl-C, which its progress callback notices): the local solves end after their
// current iteration (as Ceres' USER_FAILURE), the multistart after its current batch, and the
// caller's RunObserver::stage_finished then stops the run. One flag per process.
#pragma once

#include <atomic>

namespace vesselid {

inline std::atomic<bool>& StopFlag() {
  static std::atomic<bool> flag{false};
  return flag;
}
inline void RequestStop() { StopFlag().store(true); }
inline void ClearStopRequest() { StopFlag().store(false); }
inline bool StopRequested() { return StopFlag().load(std::memory_order_relaxed); }

}  // namespace vesselid

// A request to stop the running identification early, made from outside it (the Python
// package's Ctrl-C, which its progress callback notices): the local solves end after their
// current iteration (as Ceres' USER_FAILURE), the multistart after its current batch, and the
// caller's RunObserver::stage_finished then stops the run. One flag per process; a global
// start's screening also stops at the request, point by point.
#pragma once

#include <atomic>
#include <functional>
#include <utility>

namespace vesselid {

inline std::atomic<bool>& StopFlag() {
  static std::atomic<bool> flag{false};
  return flag;
}
inline void RequestStop() { StopFlag().store(true); }
inline void ClearStopRequest() { StopFlag().store(false); }
inline bool StopRequested() { return StopFlag().load(std::memory_order_relaxed); }

// The embedding program's own check for a stop, for work that runs long without reporting
// progress (a global start's screening): the Python package's looks for a pending Ctrl-C,
// which only Python's main thread can see. Set on the thread that runs the work, for its
// duration, by ScopedStopPoll: one per thread, so that runs on other threads neither replace
// nor end it.
inline std::function<bool()>& StopPoll() {
  thread_local std::function<bool()> poll;
  return poll;
}

// StopRequested(), after asking this thread's embedding program's check, if any (the thread
// that started the run: where the check can see its program's signals).
inline bool PollStopRequest() {
  if (!StopRequested() && StopPoll() && StopPoll()()) RequestStop();
  return StopRequested();
}

// Sets the embedding program's check while in scope.
class ScopedStopPoll {
 public:
  explicit ScopedStopPoll(std::function<bool()> poll) { StopPoll() = std::move(poll); }
  ~ScopedStopPoll() { StopPoll() = nullptr; }
  ScopedStopPoll(const ScopedStopPoll&) = delete;
  ScopedStopPoll& operator=(const ScopedStopPoll&) = delete;
};

}  // namespace vesselid

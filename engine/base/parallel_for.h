// Runs body(0) ... body(count - 1) on a pool of threads, for work below the study layer (a
// stage's bootstrap replicates, held-out runs). Each index is claimed once from a shared
// counter; the body writes only its own index's slot, so results do not depend on the thread
// count. The first exception a body throws is rethrown on the calling thread after every
// thread has joined.
//
// One level owns the cores: inside a worker (of ParallelFor or of a study's RunCases,
// ParallelWorkerScope) a request for "the machine's cores" (threads <= 0) gets one thread, so
// that nested parallel work (a study case's solve, a replicate's Ceres evaluation) does not
// oversubscribe the machine.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace vesselid {

// Marks the current thread as a parallel worker while in scope.
class ParallelWorkerScope {
 public:
  ParallelWorkerScope() : outer_(active()) { active() = true; }
  ~ParallelWorkerScope() { active() = outer_; }
  ParallelWorkerScope(const ParallelWorkerScope&) = delete;
  ParallelWorkerScope& operator=(const ParallelWorkerScope&) = delete;

  static bool& active() {
    thread_local bool in_worker = false;
    return in_worker;
  }

 private:
  bool outer_;
};

// threads <= 0: the machine's cores, or one inside a parallel worker.
inline int ParallelThreads(int threads) {
  if (threads > 0) return threads;
  if (ParallelWorkerScope::active()) return 1;
  return std::max(1u, std::thread::hardware_concurrency());
}

inline void ParallelFor(int count, int threads, const std::function<void(int)>& body) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&]() {
    for (int i = next++; i < count; i = next++) {
      try {
        body(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  const int pool_size = std::min(ParallelThreads(threads), std::max(1, count));
  if (pool_size == 1) {
    worker();  // on the caller's thread alone: nested work may still use the cores
  } else {
    auto marked = [&]() {
      const ParallelWorkerScope scope;
      worker();
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < pool_size; ++t) pool.emplace_back(marked);
    marked();
    for (std::thread& t : pool) t.join();
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace vesselid

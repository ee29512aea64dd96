// Runs body(0) ... body(count - 1) on a pool of threads, for work below the study layer (a
// stage's bootstrap replicates). Each index is claimed once from a shared counter; the body
// writes only its own index's slot, so results do not depend on the thread count. The first
// exception a body throws is rethrown on the calling thread after every thread has joined.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace vesselid {

// threads <= 0: the machine's cores.
inline int ParallelThreads(int threads) {
  if (threads > 0) return threads;
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
  std::vector<std::thread> pool;
  for (int t = 1; t < pool_size; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace vesselid

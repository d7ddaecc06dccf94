#include "util/threading.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

namespace colmap_gcn {

int EffectiveNumThreads(int num_threads) {
  if (num_threads > 0) return num_threads;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

namespace internal {

void ParallelForImpl(int begin,
                     int end,
                     int num_threads,
                     const std::function<void(int index, int thread)>& fn) {
  if (end <= begin) return;
  const int num_threads_used =
      std::min(EffectiveNumThreads(num_threads), end - begin);
  if (num_threads_used == 1) {
    for (int index = begin; index < end; ++index) fn(index, 0);
    return;
  }
  std::atomic<int> next(begin);
  std::atomic<bool> failed(false);
  std::mutex error_mutex;
  int error_index = std::numeric_limits<int>::max();
  std::exception_ptr error;
  auto worker = [&](int thread) {
    while (!failed.load()) {
      const int index = next.fetch_add(1);
      if (index >= end) return;
      try {
        fn(index, thread);
      } catch (...) {
        // Every index below one that was handed out has been handed out
        // too, so the lowest failing index always runs and is kept.
        std::lock_guard<std::mutex> lock(error_mutex);
        if (index < error_index) {
          error_index = index;
          error = std::current_exception();
        }
        failed = true;
      }
    }
  };
  std::vector<std::thread> workers;
  workers.reserve(num_threads_used);
  for (int thread = 0; thread < num_threads_used; ++thread) {
    workers.emplace_back(worker, thread);
  }
  for (std::thread& thread : workers) thread.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace internal
}  // namespace colmap_gcn

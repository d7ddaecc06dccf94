#pragma once

#include <functional>
#include <type_traits>

namespace colmap_gcn {

// The thread count an option asks for: num_threads <= 0 (options use -1)
// means every hardware thread. Always >= 1.
int EffectiveNumThreads(int num_threads);

// Runs fn(index) or fn(index, thread) for every index in [begin, end) on
// min(EffectiveNumThreads(num_threads), end - begin) threads; `thread` is
// the worker's number, for per-thread scratch buffers. Indices are handed
// out one at a time in increasing order, so the partition of the work is
// the index range itself, never the thread count: fn writes only to slots
// owned by its index (scratch aside), and results are identical for any
// thread count.
//
// Exceptions cross the pool: when fn throws, no further index is started;
// after every worker has finished, the exception of the lowest failing
// index is rethrown in the caller (the one a sequential loop would throw).
template <typename Fn>
void ParallelFor(int begin, int end, int num_threads, const Fn& fn);

namespace internal {
void ParallelForImpl(int begin,
                     int end,
                     int num_threads,
                     const std::function<void(int index, int thread)>& fn);
}  // namespace internal

template <typename Fn>
void ParallelFor(int begin, int end, int num_threads, const Fn& fn) {
  if constexpr (std::is_invocable_v<const Fn&, int, int>) {
    internal::ParallelForImpl(begin, end, num_threads, fn);
  } else {
    internal::ParallelForImpl(
        begin, end, num_threads, [&fn](int index, int) { fn(index); });
  }
}

}  // namespace colmap_gcn

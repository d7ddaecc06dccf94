#include "util/threading.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "util/error.h"

namespace colmap_gcn {
namespace {

TEST(EffectiveNumThreads, MinusOneIsAllCores) {
  EXPECT_EQ(EffectiveNumThreads(3), 3);
  EXPECT_EQ(EffectiveNumThreads(1), 1);
  const int all =
      std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  EXPECT_EQ(EffectiveNumThreads(-1), all);
  EXPECT_EQ(EffectiveNumThreads(0), all);
}

TEST(ParallelFor, RunsEveryIndexOnceWithValidThreadIds) {
  for (int num_threads : {1, 2, 3, 8, -1}) {
    std::vector<std::atomic<int>> runs(101);
    std::atomic<bool> bad_thread(false);
    ParallelFor(5, 101, num_threads, [&](int i, int thread) {
      if (thread < 0 || thread >= EffectiveNumThreads(num_threads)) {
        bad_thread = true;
      }
      ++runs[i];
    });
    for (int i = 0; i < 101; ++i) {
      EXPECT_EQ(runs[i].load(), i >= 5 ? 1 : 0) << i << " " << num_threads;
    }
    EXPECT_FALSE(bad_thread);
  }
  // Empty and reversed ranges run nothing.
  int calls = 0;
  ParallelFor(3, 3, 4, [&](int) { ++calls; });
  ParallelFor(5, 2, 4, [&](int) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(ParallelFor, ResultsDoNotDependOnTheThreadCount) {
  const auto compute = [](int num_threads) {
    std::vector<double> out(1000);
    ParallelFor(0, 1000, num_threads, [&](int i) {
      double value = 0;
      for (int j = 1; j <= 200; ++j) value += std::sin(i * 0.001 * j) / j;
      out[i] = value;
    });
    return out;
  };
  const std::vector<double> reference = compute(1);
  for (int num_threads : {2, 3, 7, -1}) {
    EXPECT_EQ(compute(num_threads), reference) << num_threads;
  }
}

TEST(ParallelFor, RethrowsTheLowestFailingIndexInTheCaller) {
  for (int num_threads : {1, 2, 4, 16}) {
    for (int repeat = 0; repeat < 20; ++repeat) {
      std::atomic<int> started(0);
      try {
        ParallelFor(0, 200, num_threads, [&](int i) {
          ++started;
          if (i == 37 || i == 38 || i == 150) {
            ThrowError("index ", i, " failed");
          }
        });
        FAIL() << "no exception";
      } catch (const Error& error) {
        EXPECT_EQ(std::string(error.what()), "index 37 failed") << num_threads;
      }
    }
  }
}

TEST(ParallelFor, StopsHandingOutIndicesAfterAFailure) {
  // Index 0 fails at once while every other index takes 20 ms: reaching all
  // 200 would need the failing worker to stall for over a second.
  std::atomic<int> started(0);
  EXPECT_THROW(
      ParallelFor(0,
                  200,
                  4,
                  [&](int i) {
                    ++started;
                    if (i == 0) ThrowError("index 0 failed");
                    std::this_thread::sleep_for(std::chrono::milliseconds(20));
                  }),
      Error);
  EXPECT_LT(started.load(), 200);
}

TEST(ParallelFor, PassesNonErrorExceptionsUnchanged) {
  EXPECT_THROW(ParallelFor(0,
                           10,
                           4,
                           [](int i) {
                             if (i == 3) throw std::out_of_range("x");
                           }),
               std::out_of_range);
}

}  // namespace
}  // namespace colmap_gcn

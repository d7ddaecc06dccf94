#pragma once

#include <cmath>
#include <cstdint>

#include "util/random.h"

namespace colmap_gcn {

// A small, platform-independent random number generator (SplitMix64) with
// its own distributions, so that synthetic scenes are byte-identical across
// standard libraries (std::uniform_*_distribution are implementation-defined).
class SyntheticRandom {
 public:
  explicit SyntheticRandom(uint64_t seed) : state_(seed) {}

  // A generator for a sub-stream, e.g. SyntheticRandom(Mix(seed, image_idx)).
  static uint64_t Mix(uint64_t a, uint64_t b) {
    return SplitMix64Mix(a * kSplitMix64Increment + b + 0x632BE59BD9B4E019ULL);
  }

  uint64_t Next() { return SplitMix64(&state_); }

  // Uniform in [0, 1).
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
  double Uniform(double a, double b) { return a + (b - a) * Uniform(); }
  // Uniform integer in [a, b] (inclusive).
  int UniformInt(int a, int b) {
    return a + static_cast<int>(Next() % static_cast<uint64_t>(b - a + 1));
  }

 private:
  uint64_t state_;
};

}  // namespace colmap_gcn

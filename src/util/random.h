#pragma once

#include <cstdint>

namespace colmap_gcn {

// SplitMix64 (Steele, Lea and Flood 2014): a tiny generator whose output is
// the same on every platform and standard library, for anything whose
// results must repeat exactly (synthetic scenes, shuffled blocks). Its
// constants define the streams that files and tests pin, so they must not
// change.
constexpr uint64_t kSplitMix64Increment = 0x9E3779B97F4A7C15ULL;

// The output function: a bijective mix of a 64-bit value.
constexpr uint64_t SplitMix64Mix(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Advances *state and returns the next value of its stream.
inline uint64_t SplitMix64(uint64_t* state) {
  *state += kSplitMix64Increment;
  return SplitMix64Mix(*state);
}

}  // namespace colmap_gcn

#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace colmap_gcn {

// A fast 64-bit hash for cache keys and file checksums (FNV-1a over 64-bit
// words with a final avalanche). Not cryptographic: it detects changed
// features and corrupt files, not tampering. Stable across platforms of the
// same endianness, which is all the caches need.
inline uint64_t HashBytes(const void* data,
                          size_t size,
                          uint64_t seed = 0xcbf29ce484222325ULL) {
  const uint64_t kPrime = 0x100000001b3ULL;
  const unsigned char* bytes = static_cast<const unsigned char*>(data);
  uint64_t hash = seed ^ (size * 0x9e3779b97f4a7c15ULL);
  size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    uint64_t word;
    std::memcpy(&word, bytes + i, 8);
    hash = (hash ^ word) * kPrime;
    hash ^= hash >> 29;
  }
  for (; i < size; ++i) {
    hash = (hash ^ bytes[i]) * kPrime;
  }
  hash ^= hash >> 33;
  hash *= 0xff51afd7ed558ccdULL;
  hash ^= hash >> 33;
  return hash;
}

inline uint64_t HashString(const std::string& str, uint64_t seed) {
  return HashBytes(str.data(), str.size(), seed);
}

inline uint64_t HashCombine(uint64_t seed, uint64_t value) {
  return HashBytes(&value, sizeof(value), seed);
}

}  // namespace colmap_gcn

#pragma once

#include <cstdint>

namespace colmap_gcn {

// The one key of an unordered pair of row indices (or ids) in [0, 2^32):
// min << 32 | max, the same for (i, j) and (j, i). COLMAP's pair_id of two
// image ids is ImagePairToPairId (scene/database.h).
inline uint64_t PairKey(int i, int j) {
  const uint64_t a = static_cast<uint64_t>(i < j ? i : j);
  const uint64_t b = static_cast<uint64_t>(i < j ? j : i);
  return (a << 32) | b;
}

}  // namespace colmap_gcn

#include "pairing/pairing.h"

#include <algorithm>

namespace colmap_gcn {

std::vector<ImagePair> PairGenerator::AllPairs() {
  Reset();
  std::vector<ImagePair> pairs;
  while (!HasFinished()) {
    const std::vector<ImagePair> block = Next();
    pairs.insert(pairs.end(), block.begin(), block.end());
  }
  return pairs;
}

std::vector<ImagePair> NextPairBlock(const std::vector<ImagePair>& pairs,
                                     const int block_size,
                                     size_t* pair_idx) {
  const size_t begin = std::min(*pair_idx, pairs.size());
  const size_t end =
      std::min(pairs.size(), begin + static_cast<size_t>(block_size));
  *pair_idx = end;
  return std::vector<ImagePair>(pairs.begin() + begin, pairs.begin() + end);
}

}  // namespace colmap_gcn

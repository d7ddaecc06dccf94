#include "adaptive_test_scenes.h"

namespace colmap_gcn {
namespace test {

std::vector<std::vector<ImagePair>> RunToTheEnd(
    AdaptivePairGenerator* generator,
    const std::function<PairVerification(const ImagePair&)>& verify) {
  std::vector<std::vector<ImagePair>> blocks;
  generator->Reset();
  while (!generator->HasFinished()) {
    blocks.push_back(generator->Next());
    std::vector<PairVerification> results;
    for (const ImagePair& pair : blocks.back()) results.push_back(verify(pair));
    generator->Observe(results);
    if (blocks.size() > 1000) break;  // a loop that never ends fails below
  }
  return blocks;
}

std::vector<ImagePair> Flatten(
    const std::vector<std::vector<ImagePair>>& blocks) {
  std::vector<ImagePair> pairs;
  for (const auto& block : blocks) {
    pairs.insert(pairs.end(), block.begin(), block.end());
  }
  return pairs;
}

}  // namespace test
}  // namespace colmap_gcn

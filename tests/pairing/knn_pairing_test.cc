#include "pairing/knn_pairing.h"

#include <gtest/gtest.h>

#include <set>

#include "../retrieval/retrieval_test_utils.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

TEST(KnnGraphToPairs, DeduplicatesUnorderedPairs) {
  KnnGraph graph;
  graph.indices.resize(3, 2);
  graph.similarities.setZero(3, 2);
  graph.indices << 1, 2, 0, 2, 1, 0;
  const std::vector<ImagePair> pairs = KnnGraphToPairs(graph, {10, 20, 30});
  EXPECT_EQ(pairs, (std::vector<ImagePair>{{10, 20}, {10, 30}, {20, 30}}));
}

TEST(KnnPairGenerator, TopKPerImageInBlocks) {
  // Points on a line: the neighbours of each are its closest indices.
  EmbeddingMatrix x(20, 2);
  for (int i = 0; i < 20; ++i) {
    const float angle = 0.05f * i;
    x(i, 0) = std::cos(angle);
    x(i, 1) = std::sin(angle);
  }
  std::vector<image_t> ids;
  for (int i = 0; i < 20; ++i) ids.push_back(100 + i);
  KnnPairingOptions options;
  options.k = 2;
  options.block_size = 7;
  KnnPairGenerator generator(options, x, ids);
  const std::vector<ImagePair> pairs = generator.AllPairs();
  std::set<std::pair<image_t, image_t>> unordered;
  for (const auto& [a, b] : pairs) {
    EXPECT_NE(a, b);
    EXPECT_TRUE(unordered.insert({std::min(a, b), std::max(a, b)}).second);
  }
  // Neighbours at distance 1 and 2 along the line (ties -> lower index).
  std::set<std::pair<image_t, image_t>> expected;
  for (int i = 0; i < 20; ++i) {
    std::vector<int> candidates;
    for (int d : {1, 2}) {
      for (int j : {i - d, i + d}) {
        if (j >= 0 && j < 20) candidates.push_back(j);
      }
    }
    std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
      return std::abs(a - i) < std::abs(b - i) ||
             (std::abs(a - i) == std::abs(b - i) && a < b);
    });
    for (int n = 0; n < 2; ++n) {
      const int j = candidates[n];
      expected.insert({100 + std::min(i, j), 100 + std::max(i, j)});
    }
  }
  EXPECT_EQ(unordered, expected);
  generator.Reset();
  EXPECT_EQ(generator.Next().size(), 7u);
}

TEST(KnnPairGenerator, FromDatabaseWithSelfTrainedVlad) {
  const TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "db.db");
  std::vector<std::pair<std::string, FeatureDescriptors>> images;
  for (int i = 0; i < 5; ++i) {
    images.emplace_back("i" + std::to_string(i),
                        test::RandomDescriptors(100, 4, i));
  }
  test::CreateDescriptorDatabase(path, images);
  KnnPairingOptions options;
  options.k = 10;  // capped at N - 1: all pairs
  options.vlad.num_words = 4;
  options.use_cache = false;
  const Database database(path);
  KnnPairGenerator generator(options, database);
  EXPECT_EQ(generator.AllPairs().size(), 10u);
  EXPECT_FALSE(ExistsFile(SelfTrainedModelPath(path)));
}

}  // namespace
}  // namespace colmap_gcn

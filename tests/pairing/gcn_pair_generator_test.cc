#include "pairing/gcn_pair_generator.h"

#include <map>
#include <set>

#include <gtest/gtest.h>

#include "gcn/gcn_test_utils.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

struct Data {
  std::vector<image_t> ids;
  EmbeddingMatrix embeddings;
  GcnModel model;
};

Data MakeData(float fc2_bias) {
  Data data;
  std::vector<int> clusters;
  data.embeddings =
      test::ClusteredEmbeddings({10, 25, 6, 19}, 16, 0.5f, 21, &clusters);
  for (int i = 0; i < data.embeddings.rows(); ++i) {
    data.ids.push_back(1000 - 7 * i);  // not sorted, not contiguous
  }
  data.model =
      InitializeGcnModel(test::SmallShape(16), GcnAggregation::kSymmetric, 2);
  test::RandomizeModel(&data.model, 5);
  data.model.params.Fc2Bias() = fc2_bias;
  return data;
}

// Checks uniqueness and returns the degree of every image.
std::map<image_t, int> CheckPairs(const std::vector<ImagePair>& pairs,
                                  const std::vector<image_t>& ids) {
  std::set<std::pair<image_t, image_t>> seen;
  std::map<image_t, int> degree;
  const std::set<image_t> valid(ids.begin(), ids.end());
  for (const auto& [a, b] : pairs) {
    EXPECT_NE(a, b);
    EXPECT_TRUE(valid.count(a) && valid.count(b));
    EXPECT_TRUE(seen.insert({std::min(a, b), std::max(a, b)}).second)
        << "duplicate pair " << a << " " << b;
    ++degree[a];
    ++degree[b];
  }
  return degree;
}

TEST(GcnPairGenerator, EachPairOnceInBlocksWithScores) {
  const Data data = MakeData(0.f);
  GcnPairingOptions options;
  options.k1 = 10;
  options.k2 = 3;
  options.u = 4;
  options.block_size = 7;
  options.min_pairs_per_image = 0;
  GcnPairGenerator generator(options, data.ids, data.embeddings, data.model);
  std::vector<ImagePair> pairs;
  while (!generator.HasFinished()) {
    const auto block = generator.Next();
    EXPECT_LE(block.size(), 7u);
    EXPECT_FALSE(block.empty());
    pairs.insert(pairs.end(), block.begin(), block.end());
  }
  EXPECT_TRUE(generator.Next().empty());
  CheckPairs(pairs, data.ids);
  EXPECT_EQ(generator.AllPairs(), pairs);
  const auto& scored = generator.ScoredPairs();
  ASSERT_EQ(scored.size(), pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    EXPECT_EQ(scored[i].image_id1, pairs[i].first);
    EXPECT_EQ(scored[i].image_id2, pairs[i].second);
    EXPECT_GE(scored[i].score, 0.5f);
    EXPECT_TRUE(scored[i].above_threshold);
  }
  EXPECT_GT(generator.Stats().num_candidates,
            generator.Stats().num_above_threshold);
  EXPECT_GT(pairs.size(), 0u);
  EXPECT_EQ(generator.Stats().num_fallback, 0);
}

TEST(GcnPairGenerator, MinPairsPerImageKeepsEveryImageConnected) {
  // A large negative bias: no pair clears the threshold.
  const Data data = MakeData(-100.f);
  GcnPairingOptions options;
  options.k1 = 10;
  options.k2 = 3;
  options.u = 4;
  options.min_pairs_per_image = 3;
  GcnPairGenerator generator(options, data.ids, data.embeddings, data.model);
  const auto pairs = generator.AllPairs();
  const auto degree = CheckPairs(pairs, data.ids);
  EXPECT_EQ(generator.Stats().num_above_threshold, 0);
  EXPECT_EQ(generator.Stats().num_fallback, static_cast<int>(pairs.size()));
  ASSERT_EQ(degree.size(), data.ids.size());
  for (const auto& [id, d] : degree) EXPECT_GE(d, 3) << id;
  EXPECT_LE(pairs.size(), data.ids.size() * 3);

  // Same with one thread: identical output.
  options.num_threads = 1;
  EXPECT_EQ(GcnPairGenerator(options, data.ids, data.embeddings, data.model)
                .AllPairs(),
            pairs);
}

TEST(GcnPairGenerator, SmallCollectionCapsK1AndAllPass) {
  Data data = MakeData(100.f);
  data.embeddings.conservativeResize(4, Eigen::NoChange);
  data.ids.resize(4);
  GcnPairingOptions options;  // k1 = 100 > N - 1
  GcnPairGenerator generator(options, data.ids, data.embeddings, data.model);
  const auto pairs = generator.AllPairs();
  CheckPairs(pairs, data.ids);
  EXPECT_EQ(pairs.size(), 6u);  // all 4 * 3 / 2 pairs

  data.ids.resize(1);
  data.embeddings.conservativeResize(1, Eigen::NoChange);
  EXPECT_TRUE(GcnPairGenerator(options, data.ids, data.embeddings, data.model)
                  .AllPairs()
                  .empty());
}

TEST(GcnPairGenerator, RejectsMismatchedInput) {
  const Data data = MakeData(0.f);
  GcnPairingOptions options;
  EmbeddingMatrix wrong_dim(data.ids.size(), 8);
  wrong_dim.setConstant(0.25f);
  EXPECT_THROW(GcnPairGenerator(options, data.ids, wrong_dim, data.model),
               Error);
  std::vector<image_t> short_ids(data.ids.begin(), data.ids.end() - 1);
  EXPECT_THROW(
      GcnPairGenerator(options, short_ids, data.embeddings, data.model), Error);
  std::vector<image_t> duplicate_ids = data.ids;
  duplicate_ids[1] = duplicate_ids[0];
  EXPECT_THROW(
      GcnPairGenerator(options, duplicate_ids, data.embeddings, data.model),
      Error);
}

}  // namespace
}  // namespace colmap_gcn

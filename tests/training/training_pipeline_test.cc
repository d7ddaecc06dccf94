#include "training/gcn_training.h"

#include <set>

#include <gtest/gtest.h>

#include "gcn/gcn_test_utils.h"

namespace colmap_gcn {
namespace {

std::set<std::pair<int, int>> AsSet(
    const std::vector<std::pair<int, int>>& pairs) {
  std::set<std::pair<int, int>> set;
  for (const auto& [i, j] : pairs) {
    EXPECT_TRUE(set.insert({std::min(i, j), std::max(i, j)}).second)
        << "duplicate " << i << " " << j;
  }
  return set;
}

// Four clusters; the matchable pairs are those within a cluster.
GcnTrainingScene ClusteredScene() {
  GcnTrainingScene scene;
  std::vector<int> cluster_of;
  scene.embeddings =
      test::ClusteredEmbeddings({8, 12, 5, 9}, 16, 0.6f, 3, &cluster_of);
  for (int i = 0; i < scene.embeddings.rows(); ++i) {
    for (int j = i + 1; j < scene.embeddings.rows(); ++j) {
      if (cluster_of[i] == cluster_of[j])
        scene.positive_pairs.push_back({i, j});
    }
  }
  return scene;
}

TEST(TrainingPipeline, ScorePairSetCountsEachUnorderedPairOnce) {
  GcnTrainingScene scene;
  scene.embeddings = EmbeddingMatrix::Zero(5, 2);
  scene.positive_pairs = {{0, 1}, {2, 3}, {1, 4}};
  // (1, 0) repeats (0, 1); (2, 2) is no pair.
  const PairSetScores scores =
      ScorePairSet({{0, 1}, {1, 0}, {3, 2}, {0, 4}, {2, 2}}, scene);
  EXPECT_EQ(scores.num_pairs, 3u);
  EXPECT_EQ(scores.num_true_positives, 2u);
  EXPECT_EQ(scores.num_positives, 3u);
  EXPECT_DOUBLE_EQ(scores.Precision(), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(scores.Recall(), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(scores.F(), 2.0 / 3.0);
  EXPECT_EQ(ScorePairSet({}, scene).F(), 0.0);
}

TEST(TrainingPipeline, TopKPairsIsTheUnionOfEveryImagesNeighbours) {
  const GcnTrainingScene scene = ClusteredScene();
  const int n = static_cast<int>(scene.embeddings.rows());
  for (const int k : {1, 3, 7, n - 1, n + 5}) {
    const KnnGraph graph =
        test::BruteForceKnn(scene.embeddings, std::min(k, n - 1));
    std::set<std::pair<int, int>> expected;
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < graph.K(); ++c) {
        const int j = graph.indices(i, c);
        expected.insert({std::min(i, j), std::max(i, j)});
      }
    }
    for (const int threads : {1, 2}) {
      EXPECT_EQ(AsSet(TopKPairs(scene.embeddings, k, threads)), expected)
          << "k " << k;
    }
  }
  EXPECT_EQ(AsSet(TopKPairs(scene.embeddings, n - 1, 1)).size(),
            static_cast<size_t>(n * (n - 1) / 2));
  EXPECT_TRUE(TopKPairs(scene.embeddings, 0, 1).empty());
}

TEST(TrainingPipeline, MostSimilarPairsAreTheTopOfTheSimilarityOrder) {
  const GcnTrainingScene scene = ClusteredScene();
  const auto pairs = MostSimilarPairs(scene.embeddings, 20);
  ASSERT_EQ(AsSet(pairs).size(), 20u);
  float lowest_kept = 2.f;
  for (const auto& [i, j] : pairs) {
    lowest_kept = std::min(
        lowest_kept, scene.embeddings.row(i).dot(scene.embeddings.row(j)));
  }
  const std::set<std::pair<int, int>> kept = AsSet(pairs);
  for (int i = 0; i < scene.embeddings.rows(); ++i) {
    for (int j = i + 1; j < scene.embeddings.rows(); ++j) {
      if (kept.count({i, j})) continue;
      EXPECT_LE(scene.embeddings.row(i).dot(scene.embeddings.row(j)),
                lowest_kept + 1e-6f);
    }
  }
}

TEST(TrainingPipeline, ThresholdSelectionMaximisesMeanF) {
  const GcnTrainingScene scene = ClusteredScene();
  GcnModel model =
      InitializeGcnModel(test::SmallShape(16), GcnAggregation::kSymmetric, 4);
  test::RandomizeModel(&model, 11);
  model.info.test_k1 = 10;
  model.info.test_k2 = 3;
  model.info.test_u = 4;
  model.info.threshold = 0.5f;

  const auto candidates = GcnCandidatePairs(model, scene, 2);
  ASSERT_FALSE(candidates.empty());
  // Candidates are the threshold-0 pair set; thresholds only filter it, as
  // the pair generator does at its own threshold.
  EXPECT_EQ(PairsAtThreshold(candidates, 0.f).size(), candidates.size());
  EXPECT_EQ(AsSet(PairsAtThreshold(candidates, 0.5f)),
            AsSet(GcnRetrievedPairs(model, scene, 1)));
  EXPECT_TRUE(PairsAtThreshold(candidates, 1.01f).empty());

  const float selected = SelectGcnThreshold(model, {scene, scene}, 1);
  EXPECT_EQ(selected, SelectGcnThreshold(model, {scene}, 2));
  const double selected_f =
      ScorePairSet(PairsAtThreshold(candidates, selected), scene).F();
  for (int step = 1; step <= 19; ++step) {
    EXPECT_LE(
        ScorePairSet(PairsAtThreshold(candidates, 0.05f * step), scene).F(),
        selected_f + 1e-12)
        << "threshold " << 0.05f * step;
  }
  EXPECT_EQ(SelectGcnThreshold(model, {}, 1), 0.5f);
}

}  // namespace
}  // namespace colmap_gcn

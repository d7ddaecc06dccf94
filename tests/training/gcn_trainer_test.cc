#include "training/gcn_trainer.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>

#include <gtest/gtest.h>

#include "gcn/gcn_inference.h"
#include "gcn/gcn_test_utils.h"
#include "test_utils.h"
#include "util/error.h"
#include "util/logging.h"

namespace colmap_gcn {
namespace {

// Clusters of very different sizes; same cluster = matchable. A fixed-k kNN
// cannot fit both the small and the large clusters.
GcnTrainingScene MakeScene(uint32_t seed,
                           const std::string& name,
                           float noise = 0.15f) {
  GcnTrainingScene scene;
  scene.name = name;
  std::vector<int> cluster;
  scene.embeddings = test::ClusteredEmbeddings(
      {2, 3, 2, 4, 3, 2, 3, 2, 4, 3, 2, 3, 2, 4, 3, 2, 3, 2, 25, 25},
      16,
      noise,
      seed,
      &cluster);
  for (int i = 0; i < scene.embeddings.rows(); ++i) {
    for (int j = i + 1; j < scene.embeddings.rows(); ++j) {
      if (cluster[i] == cluster[j]) scene.positive_pairs.emplace_back(i, j);
    }
  }
  return scene;
}

// A fixed-k kNN over the k1 nearest candidates of every image, with k chosen
// so that it retrieves about `retrieved` directed pairs.
struct FixedKnnScores {
  int k = 0;
  double f = 0;
  int64_t candidates_positive = 0;  // matchable pairs among the candidates
};

FixedKnnScores ScoreFixedKnn(const GcnTrainingScene& scene,
                             int64_t retrieved,
                             int k1) {
  FixedKnnScores scores;
  const int n = static_cast<int>(scene.embeddings.rows());
  scores.k = std::max(
      1, static_cast<int>(std::lround(static_cast<double>(retrieved) / n)));
  const KnnGraph knn = test::BruteForceKnn(scene.embeddings, k1);
  std::set<std::pair<int, int>> positives(scene.positive_pairs.begin(),
                                          scene.positive_pairs.end());
  int64_t tp = 0;
  for (int q = 0; q < n; ++q) {
    for (int i = 0; i < k1; ++i) {
      const int j = knn.indices(q, i);
      const bool positive =
          positives.count({std::min(q, j), std::max(q, j)}) > 0;
      scores.candidates_positive += positive;
      if (i < scores.k) tp += positive;
    }
  }
  const double precision = static_cast<double>(tp) / (scores.k * n);
  const double recall = static_cast<double>(tp) /
                        std::max<int64_t>(1, scores.candidates_positive);
  scores.f = precision + recall > 0
                 ? 2 * precision * recall / (precision + recall)
                 : 0.0;
  return scores;
}

GcnTrainingOptions SmallOptions() {
  GcnTrainingOptions options;
  options.shape = test::SmallShape(16);
  options.qes = {12, 3, 4};
  options.test_qes = {12, 3, 4};
  options.optimizer = GcnOptimizer::kAdam;
  options.learning_rate = 3e-3;
  options.weight_decay = 0;
  options.batch_size = 8;
  options.num_epochs = 12;
  options.lr_decay_epochs = {9};
  options.early_stopping_patience = 0;
  options.seed = 42;
  return options;
}

TEST(GcnTrainer, DeterministicForSeedWhateverThreads) {
  const std::vector<GcnTrainingScene> scenes = {MakeScene(1, "a"),
                                                MakeScene(2, "b")};
  GcnTrainingOptions options = SmallOptions();
  options.num_epochs = 2;
  options.optimizer = GcnOptimizer::kSgd;
  options.learning_rate = 0.01;
  options.weight_decay = 1e-4;
  options.lr_decay_epochs = {1};
  options.num_threads = 1;
  GcnTrainer trainer1(options);
  const GcnModel one = trainer1.Train(scenes);
  options.num_threads = 2;
  GcnTrainer trainer2(options);
  const GcnModel two = trainer2.Train(scenes);
  EXPECT_EQ(one.params.Values(), two.params.Values());
  EXPECT_EQ(one.input_shift, two.input_shift);
  EXPECT_EQ(one.input_scale, two.input_scale);
  ASSERT_EQ(trainer1.History().size(), 2u);
  EXPECT_EQ(trainer1.History()[1].train.loss, trainer2.History()[1].train.loss);
  EXPECT_EQ(trainer1.History()[1].validation.F(),
            trainer2.History()[1].validation.F());
  // A different seed gives a different model.
  options.seed = 43;
  EXPECT_NE(GcnTrainer(options).Train(scenes).params.Values(),
            one.params.Values());
}

TEST(GcnTrainer, LearnsClustersBetterThanFixedKnn) {
  std::vector<GcnTrainingScene> train;
  for (uint32_t seed = 11; seed < 17; ++seed) {
    train.push_back(MakeScene(seed, "t" + std::to_string(seed)));
  }
  const std::vector<GcnTrainingScene> val = {MakeScene(20, "v")};
  const GcnTrainingOptions options = SmallOptions();
  test::LogLines lines;
  GcnTrainer trainer(options);
  GcnModel model;
  {
    const ScopedLogSink capture(&lines);
    model = trainer.Train(train, val);
  }
  const auto& history = trainer.History();
  ASSERT_EQ(history.size(), 12u);
  EXPECT_GE(lines.size(), 14u);  // set-up, 12 epochs, done
  EXPECT_NE(lines[1].find("epoch 1/12"), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find("val loss"), std::string::npos) << lines[1];
  // The loss falls substantially.
  EXPECT_LT(history.back().train.loss, 0.6 * history.front().train.loss);
  EXPECT_LT(history.back().validation.loss,
            0.6 * history.front().validation.loss);

  // Held-out scene: GCN decisions vs a fixed-k kNN with the same number of
  // retrieved (directed) pairs, both over the k1 = 12 candidates.
  const GcnTrainingScene test_scene = MakeScene(30, "test");
  const GcnClassificationStats gcn =
      EvaluateGcn(model, {test_scene}, options.test_qes, 0.5f, 2);
  const FixedKnnScores knn =
      ScoreFixedKnn(test_scene, gcn.true_positives + gcn.false_positives, 12);
  const double knn_f = knn.f;
  const int64_t candidates_positive = knn.candidates_positive;
  std::cout << "held-out scene: GCN P " << gcn.Precision() << " R "
            << gcn.Recall() << " F " << gcn.F() << "; kNN k=" << knn.k << " F "
            << knn_f << std::endl;
  EXPECT_EQ(gcn.true_positives + gcn.false_negatives, candidates_positive);
  EXPECT_GT(gcn.F(), knn_f + 0.1)
      << "GCN P " << gcn.Precision() << " R " << gcn.Recall() << " F "
      << gcn.F() << " vs kNN k=" << knn.k << " F " << knn_f;
  EXPECT_GT(gcn.F(), 0.8);
  EXPECT_NE(model.info.notes.find("6 scene(s)"), std::string::npos);
}

TEST(AveragePrecision, RanksByScoreWithTiesInItemOrder) {
  // Ranked by score, ties in item order: 1, 0, 3, 2. Items 0, 1, 2 are
  // relevant: precision 1/1 at item 1, 2/2 at item 0, 3/4 at item 2.
  EXPECT_DOUBLE_EQ(AveragePrecision({0.5f, 0.9f, 0.1f, 0.5f}, {1, 1, 1, 0}),
                   (1.0 + 1.0 + 0.75) / 3);
  EXPECT_DOUBLE_EQ(AveragePrecision({0.2f, 0.8f}, {1, 0}), 0.5);
  EXPECT_EQ(AveragePrecision({0.2f, 0.8f}, {0, 0}), 0.0);
  EXPECT_EQ(AveragePrecision({}, {}), 0.0);
  EXPECT_THROW(AveragePrecision({0.2f}, {}), Error);
}

TEST(GcnTrainer, DistancePriorIsTheStartAndAKeptCandidate) {
  const std::vector<GcnTrainingScene> train = {MakeScene(11, "a"),
                                               MakeScene(12, "b")};
  const std::vector<GcnTrainingScene> val = {MakeScene(20, "v")};
  GcnTrainingOptions options = SmallOptions();
  options.shape.gcn_dims = {32, 16, 16, 16};
  options.aggregation = GcnAggregation::kRowNormalized;
  options.initialization = GcnInitialization::kDistancePrior;
  options.num_epochs = 2;
  options.learning_rate = 1e-30;  // below float resolution: no epoch can
                                  // beat the start
  options.weight_decay = 0;
  test::LogLines lines;
  GcnTrainer trainer(options);
  GcnModel model;
  {
    const ScopedLogSink capture(&lines);
    model = trainer.Train(train, val);
  }
  ASSERT_GE(lines.size(), 2u);
  EXPECT_NE(lines[1].find("epoch 0 (distance prior)"), std::string::npos)
      << lines[1];
  EXPECT_NE(model.info.notes.find("best epoch 0"), std::string::npos)
      << model.info.notes;
  // One global input scale, no shift.
  EXPECT_EQ(model.input_shift, Eigen::VectorXf::Zero(16));
  EXPECT_EQ(model.input_scale,
            Eigen::VectorXf::Constant(16, model.input_scale(0)));
  // The prior ranks the held-out scene's candidates (each query's 12
  // nearest neighbours) far better than chance (the fraction of matchable
  // candidates) and close to the embedding similarity, which is almost
  // perfect on these tight clusters (measured: 0.977 vs 0.982): it is the
  // distance plus a neighbourhood term.
  const GcnTrainingScene test_scene = MakeScene(30, "test");
  const GcnClassificationStats stats =
      EvaluateGcn(model, {test_scene}, options.test_qes, 0.5f, 2);
  const KnnGraph knn = test::BruteForceKnn(test_scene.embeddings, 12);
  const std::set<std::pair<int, int>> positives(
      test_scene.positive_pairs.begin(), test_scene.positive_pairs.end());
  double similarity_ap = 0;
  double chance = 0;
  int ranked = 0;
  for (int q = 0; q < knn.NumImages(); ++q) {
    std::vector<float> similarities;
    std::vector<uint8_t> matchable;
    for (int i = 0; i < 12; ++i) {
      const int j = knn.indices(q, i);
      similarities.push_back(knn.similarities(q, i));
      matchable.push_back(positives.count({std::min(q, j), std::max(q, j)}));
    }
    if (std::count(matchable.begin(), matchable.end(), 1) == 0) continue;
    similarity_ap += AveragePrecision(similarities, matchable);
    chance += std::count(matchable.begin(), matchable.end(), 1) / 12.0;
    ++ranked;
  }
  similarity_ap /= ranked;
  chance /= ranked;
  std::cout << "held-out AP: prior " << stats.MeanAveragePrecision()
            << ", similarity " << similarity_ap << ", chance " << chance
            << std::endl;
  EXPECT_EQ(stats.num_ranked_queries, ranked);
  EXPECT_GT(stats.MeanAveragePrecision(), chance + 0.2);
  EXPECT_GT(stats.MeanAveragePrecision(), similarity_ap - 0.02);
}

TEST(GcnTrainer, RejectsBadInput) {
  GcnTrainingOptions options = SmallOptions();
  EXPECT_THROW(GcnTrainer(options).Train({}), Error);
  GcnTrainingScene scene = MakeScene(1, "a");
  scene.positive_pairs.emplace_back(0, 1000);
  EXPECT_THROW(GcnTrainer(options).Train({scene}), Error);
  // The distance prior reads the embedding differences.
  options.initialization = GcnInitialization::kDistancePrior;
  options.structure_features = QesStructureFeatures::kReciprocalOnly;
  test::ExpectErrorContaining(
      [&] { options.Check(); },
      "structure_features must keep the embedding differences with the "
      "distance prior");
}

// Only scale-free numbers per node: a small network on them separates the
// clusters of a scene whose embeddings are spread twice as widely as the
// training scenes', where absolute distances would mislead.
TEST(GcnTrainer, StructureOnlyFeaturesTravelToAnotherScale) {
  std::vector<GcnTrainingScene> train;
  for (uint32_t seed = 11; seed < 17; ++seed) {
    train.push_back(MakeScene(seed, "t" + std::to_string(seed)));
  }
  GcnTrainingOptions options = SmallOptions();
  options.structure_features = QesStructureFeatures::kReciprocalOnly;
  options.feature_scaling = QesFeatureScaling::kQueryScale;
  options.shape = test::SmallShape(1);  // input_dim is set by the trainer
  const GcnModel model = GcnTrainer(options).Train(train, {MakeScene(20, "v")});
  EXPECT_EQ(model.shape.input_dim, 1 + kQesReciprocalDim);
  EXPECT_EQ(model.DifferenceDim(), 0);
  EXPECT_EQ(model.EmbeddingDim(), 16);

  const GcnTrainingScene wide = MakeScene(30, "wide", 0.3f);
  const GcnClassificationStats gcn =
      EvaluateGcn(model, {wide}, options.test_qes, model.info.threshold, 2);
  const FixedKnnScores knn =
      ScoreFixedKnn(wide, gcn.true_positives + gcn.false_positives, 12);
  std::cout << "wider scene: GCN F " << gcn.F() << "; kNN k=" << knn.k << " F "
            << knn.f << std::endl;
  EXPECT_GT(gcn.F(), knn.f + 0.05)
      << "GCN P " << gcn.Precision() << " R " << gcn.Recall()
      << "; kNN k=" << knn.k << " F " << knn.f;
}

// The closed choices of training parse from their names, once, and a bad
// name is one line listing the allowed ones.
TEST(GcnTrainer, ChoicesParseFromTheirNames) {
  EXPECT_EQ(ParseEnum(GcnOptimizerNames(), "adam", "--o"), GcnOptimizer::kAdam);
  EXPECT_EQ(ParseEnum(GcnInitializationNames(), "distance_prior", "--i"),
            GcnInitialization::kDistancePrior);
  EXPECT_EQ(EnumName(GcnOptimizerNames(), GcnOptimizer::kSgd), "sgd");
  test::ExpectErrorContaining(
      [] { ParseEnum(GcnOptimizerNames(), "rmsprop", "--o"); },
      "--o must be one of sgd|adam (got \"rmsprop\")");
  test::ExpectErrorContaining(
      [] { ParseEnum(GcnInitializationNames(), "bogus", "--i"); },
      "--i must be one of xavier|distance_prior (got \"bogus\")");
}

}  // namespace
}  // namespace colmap_gcn

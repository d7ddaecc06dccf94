#include "gcn/gcn_trainer.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>

#include <gtest/gtest.h>

#include "gcn/gcn_inference.h"
#include "gcn/gcn_test_utils.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

// Clusters of very different sizes; same cluster = matchable. A fixed-k kNN
// cannot fit both the small and the large clusters.
GcnTrainingScene MakeScene(uint32_t seed, const std::string& name) {
  GcnTrainingScene scene;
  scene.name = name;
  std::vector<int> cluster;
  scene.embeddings = test::ClusteredEmbeddings(
      {2, 3, 2, 4, 3, 2, 3, 2, 4, 3, 2, 3, 2, 4, 3, 2, 3, 2, 25, 25},
      16,
      0.15f,
      seed,
      &cluster);
  for (int i = 0; i < scene.embeddings.rows(); ++i) {
    for (int j = i + 1; j < scene.embeddings.rows(); ++j) {
      if (cluster[i] == cluster[j]) scene.positive_pairs.emplace_back(i, j);
    }
  }
  return scene;
}

GcnTrainingOptions SmallOptions() {
  GcnTrainingOptions options;
  options.shape = test::SmallShape(16);
  options.qes = {12, 3, 4};
  options.test_qes = {12, 3, 4};
  options.optimizer = "adam";
  options.learning_rate = 3e-3;
  options.weight_decay = 0;
  options.batch_size = 8;
  options.num_epochs = 12;
  options.lr_decay_epochs = {9};
  options.early_stopping_patience = 0;
  options.log = nullptr;
  options.seed = 42;
  return options;
}

TEST(GcnTrainer, DeterministicForSeedWhateverThreads) {
  const std::vector<GcnTrainingScene> scenes = {MakeScene(1, "a"),
                                                MakeScene(2, "b")};
  GcnTrainingOptions options = SmallOptions();
  options.num_epochs = 2;
  options.optimizer = "sgd";
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
  std::vector<std::string> lines;
  GcnTrainingOptions logged = options;
  logged.log = [&lines](const std::string& line) {
    lines.push_back(line);
    std::cout << line << std::endl;
  };
  GcnTrainer trainer(logged);
  const GcnModel model = trainer.Train(train, val);
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
  const int n = static_cast<int>(test_scene.embeddings.rows());
  const int64_t retrieved = gcn.true_positives + gcn.false_positives;
  const int k = std::max(
      1, static_cast<int>(std::lround(static_cast<double>(retrieved) / n)));
  const KnnGraph knn = test::BruteForceKnn(test_scene.embeddings, 12);
  std::set<std::pair<int, int>> positives(test_scene.positive_pairs.begin(),
                                          test_scene.positive_pairs.end());
  int64_t tp = 0, candidates_positive = 0;
  for (int q = 0; q < n; ++q) {
    for (int i = 0; i < 12; ++i) {
      const int j = knn.indices(q, i);
      const bool positive =
          positives.count({std::min(q, j), std::max(q, j)}) > 0;
      candidates_positive += positive;
      if (i < k) tp += positive;
    }
  }
  const double knn_precision = static_cast<double>(tp) / (k * n);
  const double knn_recall = static_cast<double>(tp) / candidates_positive;
  const double knn_f =
      2 * knn_precision * knn_recall / (knn_precision + knn_recall);
  std::cout << "held-out scene: GCN P " << gcn.Precision() << " R "
            << gcn.Recall() << " F " << gcn.F() << "; kNN k=" << k << " P "
            << knn_precision << " R " << knn_recall << " F " << knn_f
            << std::endl;
  EXPECT_EQ(gcn.true_positives + gcn.false_negatives, candidates_positive);
  EXPECT_GT(gcn.F(), knn_f + 0.1)
      << "GCN P " << gcn.Precision() << " R " << gcn.Recall() << " F "
      << gcn.F() << " vs kNN k=" << k << " F " << knn_f;
  EXPECT_GT(gcn.F(), 0.8);
  EXPECT_NE(model.info.notes.find("6 scene(s)"), std::string::npos);
}

TEST(GcnTrainer, RejectsBadInput) {
  GcnTrainingOptions options = SmallOptions();
  EXPECT_THROW(GcnTrainer(options).Train({}), Error);
  GcnTrainingScene scene = MakeScene(1, "a");
  scene.positive_pairs.emplace_back(0, 1000);
  EXPECT_THROW(GcnTrainer(options).Train({scene}), Error);
  options.optimizer = "rmsprop";
  EXPECT_THROW(GcnTrainer(options).Train({MakeScene(1, "a")}), Error);
}

}  // namespace
}  // namespace colmap_gcn

#include "training/gcn_training.h"

#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "gcn/gcn_test_utils.h"
#include "pairing/gcn_pair_generator.h"
#include "training/model_evaluation.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"

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
GcnTrainingScene ClusteredScene(float noise = 0.6f) {
  GcnTrainingScene scene;
  std::vector<int> cluster_of;
  scene.embeddings =
      test::ClusteredEmbeddings({8, 12, 5, 9}, 16, noise, 3, &cluster_of);
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
  const PairSetScore scores =
      ScorePairSet({{0, 1}, {1, 0}, {3, 2}, {0, 4}, {2, 2}}, scene);
  EXPECT_EQ(scores.num_pairs, 3u);
  EXPECT_EQ(scores.num_true_positives, 2u);
  EXPECT_EQ(scores.num_matchable, 3u);
  EXPECT_DOUBLE_EQ(scores.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(scores.recall, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(scores.f_measure, 2.0 / 3.0);
  EXPECT_EQ(ScorePairSet({}, scene).f_measure, 0.0);
  EXPECT_EQ(scores.num_wrong_pairs, 0u);  // the scene lists none
  scene.unrelated_pairs = {{4, 0}, {1, 2}};
  EXPECT_EQ(ScorePairSet({{0, 1}, {0, 4}, {3, 2}}, scene).num_wrong_pairs, 1u);
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

GcnModel SmallModel() {
  GcnModel model =
      InitializeGcnModel(test::SmallShape(16), GcnAggregation::kSymmetric, 4);
  test::RandomizeModel(&model, 11);
  model.info.test_k1 = 10;
  model.info.test_k2 = 3;
  model.info.test_u = 4;
  model.info.threshold = 0.5f;
  return model;
}

TEST(TrainingPipeline, ThresholdSelectionMaximisesMeanF) {
  const GcnTrainingScene scene = ClusteredScene();
  const GcnModel model = SmallModel();

  const auto candidates = GcnCandidatePairs(model, scene, 2);
  ASSERT_FALSE(candidates.empty());
  // Candidates are the threshold-0 pair set; thresholds only filter it, as
  // the pair generator does at its own threshold.
  EXPECT_EQ(PairsAtThreshold(candidates, 0.f).size(), candidates.size());
  GcnPairingOptions options = GcnPairingOptionsFromModel(model);
  options.min_pairs_per_image = 0;
  std::vector<image_t> ids(scene.embeddings.rows());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<image_t>(i + 1);
  std::set<std::pair<int, int>> generated;
  for (const auto& [id1, id2] :
       GcnPairGenerator(options, ids, scene.embeddings, model).AllPairs()) {
    generated.insert({static_cast<int>(std::min(id1, id2)) - 1,
                      static_cast<int>(std::max(id1, id2)) - 1});
  }
  EXPECT_EQ(AsSet(PairsAtThreshold(candidates, 0.5f)), generated);
  EXPECT_EQ(AsSet(GcnRetrievedPairs(model, scene, 1)), generated);
  EXPECT_TRUE(PairsAtThreshold(candidates, 1.01f).empty());

  const float selected = SelectGcnThreshold(model, {scene, scene}, 1);
  EXPECT_EQ(selected, SelectGcnThreshold(model, {scene}, 2));
  const double selected_f =
      ScorePairSet(PairsAtThreshold(candidates, selected), scene).f_measure;
  std::vector<float> grid = {0.01f, 0.02f, 0.97f, 0.98f, 0.99f, 0.999f};
  for (int step = 1; step <= 19; ++step) grid.push_back(0.05f * step);
  for (const float threshold : grid) {
    EXPECT_LE(
        ScorePairSet(PairsAtThreshold(candidates, threshold), scene).f_measure,
        selected_f + 1e-12)
        << "threshold " << threshold;
  }
  EXPECT_EQ(SelectGcnThreshold(model, {}, 1), 0.5f);
}

TEST(TrainingPipeline, MergedScenesStackImagesAndMakeCrossPairsUnrelated) {
  GcnTrainingScene a;
  a.embeddings = EmbeddingMatrix::Constant(3, 2, 1.f);
  a.positive_pairs = {{0, 1}};
  a.unrelated_pairs = {{0, 2}};
  GcnTrainingScene b;
  b.embeddings = EmbeddingMatrix::Constant(2, 2, 2.f);
  b.positive_pairs = {{1, 0}};
  const GcnTrainingScene merged = MergeTrainingScenes("a+b", {a, b});
  EXPECT_EQ(merged.name, "a+b");
  ASSERT_EQ(merged.embeddings.rows(), 5);
  EXPECT_EQ(merged.embeddings(2, 0), 1.f);
  EXPECT_EQ(merged.embeddings(3, 1), 2.f);
  EXPECT_EQ(AsSet(merged.positive_pairs),
            (std::set<std::pair<int, int>>{{0, 1}, {3, 4}}));
  // a's own unrelated pair plus all 3 x 2 pairs across the scenes.
  EXPECT_EQ(AsSet(merged.unrelated_pairs),
            (std::set<std::pair<int, int>>{
                {0, 2}, {0, 3}, {0, 4}, {1, 3}, {1, 4}, {2, 3}, {2, 4}}));
  EXPECT_EQ(merged.part_of_row, (std::vector<int>{0, 0, 0, 1, 1}));
  // Pairs across the parts are counted once, in either order.
  const PairSetScore scores =
      ScorePairSet({{0, 1}, {3, 0}, {0, 3}, {4, 2}, {3, 4}, {0, 2}}, merged);
  EXPECT_EQ(scores.num_pairs, 5u);
  EXPECT_EQ(scores.num_true_positives, 2u);
  EXPECT_EQ(scores.num_cross_scene, 2u);
  EXPECT_EQ(scores.num_wrong_pairs, 3u);
  EXPECT_EQ(ScorePairSet({{3, 0}}, a).num_cross_scene, 0u);
  b.embeddings = EmbeddingMatrix::Zero(2, 3);
  EXPECT_THROW(MergeTrainingScenes("a+b", {a, b}), Error);
}

TEST(TrainingPipeline, CollectionsAreNamedWithPlus) {
  TemporaryDirectory dir("collections_test");
  for (const char* name : {"a", "b"}) {
    const std::string scene = JoinPaths(dir.Path(), name);
    CreateDirIfNotExists(JoinPaths(scene, "labels"));
    WriteFileAtomically(JoinPaths(scene, "base.db"), "");
    WriteFileAtomically(JoinPaths(scene, "labels/labels.csv"), "");
  }
  const auto scenes = FindLabelledScenes(dir.Path(), {"a+b", "b"});
  ASSERT_EQ(scenes.size(), 2u);
  EXPECT_EQ(scenes[0].name, "a+b");
  ASSERT_EQ(scenes[0].parts.size(), 2u);
  EXPECT_EQ(scenes[0].parts[1].name, "b");
  EXPECT_EQ(scenes[0].parts[1].database_path,
            JoinPaths(JoinPaths(dir.Path(), "b"), "base.db"));
  EXPECT_TRUE(scenes[1].parts.empty());
  // Held out inside collections too.
  const auto kept = WithoutHeldOutScenes(scenes, {"b+c"});
  EXPECT_TRUE(kept.empty());
  ASSERT_EQ(WithoutHeldOutScenes(scenes, {"a"}).size(), 1u);
  EXPECT_EQ(WithoutHeldOutScenes(scenes, {"a"})[0].name, "b");
  EXPECT_EQ(WithoutHeldOutScenes(scenes, {}).size(), 2u);
  EXPECT_THROW(FindLabelledScenes(dir.Path(), {"a+a"}), Error);
  EXPECT_THROW(FindLabelledScenes(dir.Path(), {"a+c"}), Error);
  EXPECT_THROW(FindLabelledScenes(dir.Path(), {"a+"}), Error);
}

TEST(ModelEvaluation, FixedKComparisonIsConsistent) {
  GcnTrainingScene scene = ClusteredScene();
  scene.name = "clusters";
  const GcnModel model = SmallModel();
  const FixedKComparison c = CompareWithFixedK(model, scene, 100, 2);
  EXPECT_EQ(c.scene, "clusters");
  EXPECT_EQ(c.gcn.num_pairs, AsSet(GcnRetrievedPairs(model, scene, 1)).size());
  EXPECT_EQ(c.equal.num_pairs, c.gcn.num_pairs);
  // top-k= is the smallest k reaching the GCN's pair count.
  ASSERT_GT(c.equal_k, 0);
  EXPECT_GE(c.top_k_equal.num_pairs, c.gcn.num_pairs);
  if (c.equal_k > 1) {
    EXPECT_LT(TopKPairs(scene.embeddings, c.equal_k - 1, 1).size(),
              c.gcn.num_pairs);
  }
  // best k has the highest F of every k.
  const int n = static_cast<int>(scene.embeddings.rows());
  for (int k = 1; k < n; ++k) {
    EXPECT_LE(ScorePairSet(TopKPairs(scene.embeddings, k, 1), scene).f_measure,
              c.top_k_best.f_measure + 1e-12);
  }
  EXPECT_GE(c.top_k_best.f_measure, c.top_k_equal.f_measure);
  EXPECT_GT(c.top_k_best.f_measure, 0.0);
  const std::string table = FormatFixedKComparison({c, c});
  EXPECT_NE(table.find("| clusters |"), std::string::npos) << table;
  EXPECT_NE(table.find("of 2 scenes"), std::string::npos) << table;
}

TEST(ModelEvaluation, TableShowsEachModelsThresholdAndKeptFraction) {
  GcnTrainingScene scene = ClusteredScene();
  scene.name = "clusters";
  GcnModel model = SmallModel();
  model.info.threshold = 0.25f;
  const FixedKComparison low = CompareWithFixedK(model, scene, 100, 2);
  model.info.threshold = 0.75f;
  FixedKComparison high = CompareWithFixedK(model, scene, 100, 2);
  high.scene = "clusters-high";
  EXPECT_EQ(low.num_images, static_cast<int>(scene.embeddings.rows()));
  EXPECT_EQ(low.num_candidates, GcnCandidatePairs(model, scene, 1).size());
  EXPECT_EQ(high.num_candidates, low.num_candidates);
  EXPECT_GE(low.gcn.num_pairs, high.gcn.num_pairs);
  ASSERT_GT(low.num_candidates, 0u);
  EXPECT_DOUBLE_EQ(low.KeptFraction(),
                   static_cast<double>(low.gcn.num_pairs) / low.num_candidates);
  const std::string table = FormatFixedKComparison({low, high});
  EXPECT_NE(table.find("| clusters | " + std::to_string(low.num_images) +
                       " | 0.25 | " + std::to_string(low.num_candidates) +
                       " | " + std::to_string(low.gcn.num_pairs) + " | "),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| clusters-high | " + std::to_string(low.num_images) +
                       " | 0.75 | "),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("P >= 0.85 at R >= 0.8"), std::string::npos) << table;
  EXPECT_EQ(table.find("| collection |"), std::string::npos) << table;
  high.is_collection = true;
  high.gcn.num_cross_scene = 1;
  const std::string with_collection = FormatFixedKComparison({low, high});
  EXPECT_NE(with_collection.find("| collection |"), std::string::npos);
  EXPECT_NE(with_collection.find("| clusters-high | " +
                                 std::to_string(high.num_images) + " | " +
                                 std::to_string(high.gcn.num_pairs) + " | "),
            std::string::npos)
      << with_collection;
}

TEST(ModelEvaluation, FoldsFileListsModelsAndTheirScenes) {
  TemporaryDirectory dir("folds_test");
  const std::string path = JoinPaths(dir.Path(), "folds.txt");
  WriteFileAtomically(path,
                      "# model scenes\n"
                      "a.gcnmodel s1,s2\n"
                      "\n"
                      "  b.gcnmodel   s3  \n");
  const std::vector<EvaluationFold> folds = ReadEvaluationFolds(path);
  ASSERT_EQ(folds.size(), 2u);
  EXPECT_EQ(folds[0].model_path, "a.gcnmodel");
  EXPECT_EQ(folds[0].scenes, (std::vector<std::string>{"s1", "s2"}));
  EXPECT_EQ(folds[1].model_path, "b.gcnmodel");
  EXPECT_EQ(folds[1].scenes, (std::vector<std::string>{"s3"}));
  auto error_of = [&](const std::string& text) {
    WriteFileAtomically(path, text);
    try {
      ReadEvaluationFolds(path);
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("a.gcnmodel\n").find("line 1: expected"),
            std::string::npos);
  EXPECT_NE(error_of("a.gcnmodel s1 extra\n").find("line 1: expected"),
            std::string::npos);
  EXPECT_NE(error_of("a.gcnmodel s1\nb.gcnmodel s2,s1\n")
                .find("line 2: scene s1 listed twice"),
            std::string::npos);
  EXPECT_NE(error_of("# nothing\n").find("lists no fold"), std::string::npos);
  EXPECT_THROW(ReadEvaluationFolds(JoinPaths(dir.Path(), "missing.txt")),
               Error);
}

TEST(ModelEvaluation, EqualRecallBaselineCountsWrongPairs) {
  GcnTrainingScene scene = ClusteredScene();
  scene.name = "clusters";
  // Pairs across clusters share nothing here.
  const std::set<std::pair<int, int>> positives = AsSet(scene.positive_pairs);
  const int n = static_cast<int>(scene.embeddings.rows());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (!positives.count({i, j})) scene.unrelated_pairs.push_back({i, j});
    }
  }
  const FixedKComparison c = CompareWithFixedK(SmallModel(), scene, 100, 2);
  EXPECT_EQ(c.num_unrelated_pairs, scene.unrelated_pairs.size());
  EXPECT_EQ(c.gcn.num_wrong_pairs, c.gcn.num_pairs - c.gcn.num_true_positives);
  // kNN@R: the shortest most-similar prefix reaching the GCN's recall.
  EXPECT_GE(c.equal_recall.num_true_positives, c.gcn.num_true_positives);
  EXPECT_EQ(c.equal_recall.num_wrong_pairs,
            c.equal_recall.num_pairs - c.equal_recall.num_true_positives);
  ASSERT_GT(c.equal_recall.num_pairs, 0u);
  EXPECT_LT(ScorePairSet(MostSimilarPairs(scene.embeddings,
                                          c.equal_recall.num_pairs - 1),
                         scene)
                .num_true_positives,
            c.gcn.num_true_positives);
  const std::string table = FormatFixedKComparison({c});
  EXPECT_NE(table.find("| clusters | " +
                       std::to_string(scene.unrelated_pairs.size()) + " | "),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("GCN admits fewer on"), std::string::npos) << table;
}

TEST(ModelEvaluation, BestPrecisionAtRecallTakesTheBestCut) {
  GcnTrainingScene scene;
  scene.embeddings = EmbeddingMatrix::Zero(6, 2);
  scene.positive_pairs = {{0, 1}, {2, 3}, {4, 5}, {1, 2}, {0, 5}};
  // Ranked: T F T (repeat, ignored) T F F T; running precision 1, 1/2,
  // 2/3, 3/4, 3/5, 3/6, 4/7 at recall 0.2, 0.2, 0.4, 0.6, 0.6, 0.6, 0.8.
  const std::vector<std::pair<int, int>> ranked = {
      {0, 1}, {0, 2}, {3, 2}, {1, 0}, {4, 5}, {1, 3}, {3, 5}, {1, 2}};
  EXPECT_DOUBLE_EQ(BestPrecisionAtRecall(ranked, scene, 0.2), 1.0);
  EXPECT_DOUBLE_EQ(BestPrecisionAtRecall(ranked, scene, 0.4), 3.0 / 4.0);
  EXPECT_DOUBLE_EQ(BestPrecisionAtRecall(ranked, scene, 0.6), 3.0 / 4.0);
  EXPECT_DOUBLE_EQ(BestPrecisionAtRecall(ranked, scene, 0.8), 4.0 / 7.0);
  // (0, 5) is never ranked: full recall is out of reach.
  EXPECT_EQ(BestPrecisionAtRecall(ranked, scene, 1.0), -1);
  scene.positive_pairs.clear();
  EXPECT_EQ(BestPrecisionAtRecall(ranked, scene, 0.5), -1);
}

TEST(ModelEvaluation, PrecisionAtTargetRecallIsReportedForBothRankings) {
  // Tight clusters: similarity ranks every within-cluster pair first.
  GcnTrainingScene scene = ClusteredScene(0.01f);
  scene.name = "tight";
  const GcnModel model = SmallModel();
  const FixedKComparison c = CompareWithFixedK(model, scene, 100, 2);
  EXPECT_DOUBLE_EQ(c.similarity_precision_at_recall, 1.0);
  // The GCN's value is its own candidates' ranking, cut by the labels.
  std::vector<ScoredRowPair> candidates = GcnCandidatePairs(model, scene, 1);
  std::stable_sort(candidates.begin(),
                   candidates.end(),
                   [](const ScoredRowPair& a, const ScoredRowPair& b) {
                     return a.score > b.score;
                   });
  std::vector<std::pair<int, int>> ranked;
  for (const auto& candidate : candidates) {
    ranked.emplace_back(candidate.row1, candidate.row2);
  }
  EXPECT_DOUBLE_EQ(c.gcn_precision_at_recall,
                   BestPrecisionAtRecall(ranked, scene, kPrecisionAtRecall));
  const std::string table = FormatFixedKComparison({c});
  EXPECT_NE(table.find("Best precision at recall >= 0.8"), std::string::npos)
      << table;
  EXPECT_NE(table.find("| tight | "), std::string::npos) << table;
}

TEST(ModelEvaluation, SensitivityVariesOneParameterAtATime) {
  const GcnTrainingScene scene = ClusteredScene();
  const GcnModel model = SmallModel();
  GcnSensitivityOptions options;
  options.k1_values = {2, 10};
  options.k2_values = {1};
  options.u_values = {1, 4};
  options.thresholds = {0.01, 0.5, 0.99};
  options.num_threads = 1;
  const auto points = ComputeGcnSensitivity(model, {scene}, options);
  ASSERT_EQ(points.size(), 8u);
  EXPECT_EQ(points[0].parameter, "k1");
  EXPECT_EQ(points[7].parameter, "threshold");
  // The model's own setting reproduces its pair set; thresholds only filter.
  const PairSetScore own =
      ScorePairSet(GcnRetrievedPairs(model, scene, 1), scene);
  EXPECT_DOUBLE_EQ(points[1].f, own.f_measure);  // k1 = 10
  EXPECT_DOUBLE_EQ(points[6].f, own.f_measure);  // threshold 0.5
  EXPECT_GE(points[5].pairs_per_image, points[6].pairs_per_image);
  EXPECT_GE(points[6].pairs_per_image, points[7].pairs_per_image);
  // Two neighbours per image cannot recall what ten do.
  EXPECT_LE(points[0].recall, points[1].recall + 1e-12);
  options.thresholds = {1.0};
  EXPECT_THROW(options.Check(), OptionError);

  TemporaryDirectory dir("sensitivity_test");
  WriteGcnSensitivity(points, "test", dir.Path());
  const std::string csv =
      ReadTextFile(JoinPaths(dir.Path(), "sensitivity.csv"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 9);
  for (const char* parameter : {"k1", "k2", "u", "threshold"}) {
    EXPECT_TRUE(ExistsFile(JoinPaths(
        dir.Path(), std::string("sensitivity_") + parameter + ".png")));
  }
}

}  // namespace
}  // namespace colmap_gcn

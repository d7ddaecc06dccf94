#include "training/gcn_network.h"

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "gcn/gcn_inference.h"
#include "gcn/gcn_test_utils.h"

namespace colmap_gcn {
namespace {

struct Fixture {
  EmbeddingMatrix embeddings;
  KnnGraph knn;
  GcnModel model;
};

Fixture MakeFixture(
    const GcnShape& shape,
    GcnAggregation aggregation,
    int knn_k,
    QesStructureFeatures structure = QesStructureFeatures::kNone) {
  Fixture f;
  std::vector<int> clusters;
  // 16-D embeddings when the network reads only structural values.
  const int dim = QesUsesEmbeddingDifferences(structure)
                      ? shape.input_dim - QesStructureDim(structure)
                      : 16;
  f.embeddings =
      test::ClusteredEmbeddings({12, 7, 20, 9, 15}, dim, 0.4f, 11, &clusters);
  f.knn = test::BruteForceKnn(f.embeddings, knn_k);
  f.model = InitializeGcnModel(shape, aggregation, 5);
  f.model.structure_features = structure;
  f.model.embedding.dim = dim;
  test::RandomizeModel(&f.model, 9);
  return f;
}

class GcnForwardTest : public ::testing::TestWithParam<GcnAggregation> {};

TEST_P(GcnForwardTest, OptimisedAndTrainingPathsEqualReference) {
  for (const QesStructureFeatures structure :
       {QesStructureFeatures::kNone,
        QesStructureFeatures::kReciprocal,
        QesStructureFeatures::kReciprocalOnly}) {
    for (const QesFeatureScaling scaling :
         {QesFeatureScaling::kNone, QesFeatureScaling::kQueryScale}) {
      SCOPED_TRACE(std::string(QesFeatureScalingName(scaling)) + " " +
                   QesStructureFeaturesName(structure));
      const int differences = QesUsesEmbeddingDifferences(structure) ? 16 : 0;
      Fixture f = MakeFixture(
          test::SmallShape(differences + QesStructureDim(structure)),
          GetParam(),
          10,
          structure);
      f.model.feature_scaling = scaling;
      const QesOptions qes{8, 3, 4};
      GcnScorer scorer(f.model, f.embeddings, 1);
      GcnWorkspace workspace;
      for (int q = 0; q < f.knn.NumImages(); ++q) {
        const QuerySubgraph s = BuildQuerySubgraph(f.knn, q, qes, structure);
        const GcnGraph<float> graph = MakeGcnGraph(f.model, s, f.embeddings);
        const ColVector<float> reference =
            GcnForwardReference(f.model.params, graph);
        ASSERT_EQ(reference.size(), 8);
        ColVector<float> training;
        GcnLossAndGradient<float>(
            f.model.params, graph, 1.f, nullptr, &training);
        std::vector<float> optimised;
        scorer.ScoreSubgraph(s, &workspace, &optimised);
        ASSERT_EQ(optimised.size(), 8u);
        const float scale = 1.f + reference.cwiseAbs().maxCoeff();
        for (int i = 0; i < 8; ++i) {
          EXPECT_NEAR(training(i), reference(i), 1e-5f * scale);
          EXPECT_NEAR(optimised[i], reference(i), 1e-4f * scale)
              << q << " " << i;
        }
      }
    }
  }
}

TEST_P(GcnForwardTest, OptimisedEqualsReferenceFullSizeNetwork) {
  // Paper-sized network (D = 256, 512-512-256-256, FC 256) on one query.
  GcnShape shape;
  Fixture f = MakeFixture(shape, GetParam(), 30);
  f.model = InitializeGcnModel(shape, GetParam(), 5);
  f.model.input_scale.setConstant(4.f);
  f.model.input_shift.setConstant(0.01f);
  const QesOptions qes{20, 5, 5};
  const QuerySubgraph s = BuildQuerySubgraph(f.knn, 3, qes);
  const ColVector<float> reference = GcnForwardReference(
      f.model.params, MakeGcnGraph(f.model, s, f.embeddings));
  GcnScorer scorer(f.model, f.embeddings, 1);
  GcnWorkspace workspace;
  std::vector<float> optimised;
  scorer.ScoreSubgraph(s, &workspace, &optimised);
  ASSERT_EQ(optimised.size(), 20u);
  const float scale = 1.f + reference.cwiseAbs().maxCoeff();
  for (int i = 0; i < 20; ++i) {
    EXPECT_NEAR(optimised[i], reference(i), 1e-4f * scale);
  }
}

INSTANTIATE_TEST_SUITE_P(Aggregations,
                         GcnForwardTest,
                         ::testing::Values(GcnAggregation::kSymmetric,
                                           GcnAggregation::kRowNormalized));

TEST(GcnForward, ScoreAllQueriesIndependentOfThreads) {
  const Fixture f =
      MakeFixture(test::SmallShape(16), GcnAggregation::kSymmetric, 10);
  const QesOptions qes{8, 3, 4};
  const auto one = ScoreAllQueries(f.model, f.embeddings, f.knn, qes, 1);
  const auto three = ScoreAllQueries(f.model, f.embeddings, f.knn, qes, 3);
  ASSERT_EQ(one.size(), static_cast<size_t>(f.knn.NumImages()));
  EXPECT_EQ(one, three);
  for (const auto& scores : one) {
    ASSERT_EQ(scores.size(), 8u);
    for (float p : scores) {
      EXPECT_GE(p, 0.f);
      EXPECT_LE(p, 1.f);
    }
  }
}

// Analytic gradients against central finite differences in double precision,
// every parameter of every group.
class GcnGradientTest : public ::testing::TestWithParam<GcnAggregation> {};

TEST_P(GcnGradientTest, MatchesFiniteDifferences) {
  GcnShape shape;
  shape.input_dim = 6;
  shape.gcn_dims = {8, 7, 6, 5};
  shape.fc_dim = 4;
  Fixture f = MakeFixture(shape, GetParam(), 6);
  const QesOptions qes{5, 3, 3};
  const QuerySubgraph s = BuildQuerySubgraph(f.knn, 4, qes);
  GcnGraph<double> graph =
      CastGraph<double>(MakeGcnGraph(f.model, s, f.embeddings));
  graph.labels = {1, 0, 1, 1, 0};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uniform(-0.6, 0.6);
  GcnParameters<double> params = f.model.params.Cast<double>();
  for (double& v : params.Values()) v = uniform(rng);
  const double positive_weight = 2.5;

  GcnParameters<double> gradient(shape);
  const double loss = GcnLossAndGradient<double>(
      params, graph, positive_weight, &gradient, nullptr);
  EXPECT_GT(loss, 0.0);

  const GcnParameterLayout& layout = params.Layout();
  auto group_of = [&](size_t i) -> std::string {
    for (int l = shape.NumGcnLayers() - 1; l >= 0; --l) {
      if (i >= layout.gcn_bias[l] && l < shape.NumGcnLayers() &&
          i < layout.gcn_bias[l] + shape.gcn_dims[l]) {
        return "gcn_bias" + std::to_string(l);
      }
      if (i >= layout.gcn_weight[l] && i < layout.gcn_bias[l]) {
        return "gcn_weight" + std::to_string(l);
      }
    }
    if (i >= layout.fc2_bias) return "fc2_bias";
    if (i >= layout.fc2_weight) return "fc2_weight";
    if (i >= layout.prelu) return "prelu";
    if (i >= layout.fc1_bias) return "fc1_bias";
    return "fc1_weight";
  };
  const double eps = 1e-6;
  std::map<std::string, int> checked;
  for (size_t i = 0; i < params.Size(); ++i) {
    GcnParameters<double> plus = params, minus = params;
    plus.Values()[i] += eps;
    minus.Values()[i] -= eps;
    const double lp = GcnLossAndGradient<double>(
        plus, graph, positive_weight, nullptr, nullptr);
    const double lm = GcnLossAndGradient<double>(
        minus, graph, positive_weight, nullptr, nullptr);
    const double numeric = (lp - lm) / (2 * eps);
    EXPECT_NEAR(gradient.Values()[i], numeric, 1e-6 + 1e-5 * std::abs(numeric))
        << group_of(i) << " index " << i;
    if (std::abs(numeric) > 1e-8) ++checked[group_of(i)];
  }
  // Every group has parameters with a non-zero gradient.
  for (int l = 0; l < shape.NumGcnLayers(); ++l) {
    EXPECT_GT(checked["gcn_weight" + std::to_string(l)], 0) << l;
    EXPECT_GT(checked["gcn_bias" + std::to_string(l)], 0) << l;
  }
  for (const char* group :
       {"fc1_weight", "fc1_bias", "prelu", "fc2_weight", "fc2_bias"}) {
    EXPECT_GT(checked[group], 0) << group;
  }
}

INSTANTIATE_TEST_SUITE_P(Aggregations,
                         GcnGradientTest,
                         ::testing::Values(GcnAggregation::kSymmetric,
                                           GcnAggregation::kRowNormalized));

}  // namespace
}  // namespace colmap_gcn

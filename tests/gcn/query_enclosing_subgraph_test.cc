#include "gcn/query_enclosing_subgraph.h"

#include <cmath>

#include <gtest/gtest.h>

#include "gcn/gcn_test_utils.h"
#include "util/error.h"
#include "util/option_check.h"

namespace colmap_gcn {
namespace {

// Hand-built kNN graph over 8 images, K = 3 (self excluded).
KnnGraph HandBuiltKnn() {
  KnnGraph knn;
  knn.indices.resize(8, 3);
  knn.indices << 1, 2, 3,  //
      0, 4, 2,             //
      5, 0, 6,             //
      7, 0, 1,             //
      1, 5, 0,             //
      2, 0, 6,             //
      7, 3, 5,             //
      3, 6, 0;
  knn.similarities = Eigen::MatrixXf::Constant(8, 3, 0.5f);
  return knn;
}

// The QES of image 0 in HandBuiltKnn with k1 = 2, k2 = 3, u = 2.
QuerySubgraph HandBuiltSubgraph(
    QesStructureFeatures structure = QesStructureFeatures::kNone) {
  QesOptions options;
  options.k1 = 2;
  options.k2 = 3;
  options.u = 2;
  return BuildQuerySubgraph(HandBuiltKnn(), 0, options, structure);
}

TEST(QuerySubgraph, ReciprocalFeatures) {
  // Only computed when asked for.
  EXPECT_TRUE(HandBuiltSubgraph().reciprocal.empty());
  const QuerySubgraph s = HandBuiltSubgraph(QesStructureFeatures::kReciprocal);
  ASSERT_EQ(s.nodes, (std::vector<int>{1, 2, 4, 5, 6}));
  ASSERT_EQ(s.reciprocal.size(), 5u * kQesReciprocalDim);
  // K = 3, so both overlaps use {q} + 3 nearest = {0, 1, 2, 3}; ranks are
  // log(1 + r) / log(4), r = 3 when absent.
  const float l2 = std::log(2.f) / std::log(4.f);
  const float l3 = std::log(3.f) / std::log(4.f);
  const std::vector<std::vector<float>> expected = {
      {0.f, 0.f, 3.f / 5.f, 3.f / 5.f},   // 1: row 0 4 2
      {l2, l2, 2.f / 6.f, 2.f / 6.f},     // 2: row 5 0 6
      {1.f, l3, 2.f / 6.f, 2.f / 6.f},    // 4: row 1 5 0
      {1.f, l2, 2.f / 6.f, 2.f / 6.f},    // 5: row 2 0 6
      {1.f, 1.f, 1.f / 7.f, 1.f / 7.f}};  // 6: row 7 3 5
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < kQesReciprocalDim; ++j) {
      EXPECT_NEAR(
          s.reciprocal[i * kQesReciprocalDim + j], expected[i][j], 1e-6f)
          << "node " << s.nodes[i] << " feature " << j;
    }
  }
  // Appended after the embedding differences.
  const EmbeddingMatrix e = EmbeddingMatrix::Identity(8, 8);
  const auto x = QesNodeFeatures(
      s, e, QesFeatureScaling::kNone, QesStructureFeatures::kReciprocal);
  ASSERT_EQ(x.cols(), 8 + kQesReciprocalDim);
  EXPECT_TRUE(x.leftCols(8).isApprox(QesFeatures(s, e)));
  EXPECT_NEAR(x(0, 8 + 2), 0.6f, 1e-6f);
  EXPECT_EQ(QesNodeFeatures(
                s, e, QesFeatureScaling::kNone, QesStructureFeatures::kNone)
                .cols(),
            8);
  // Only structure: the distance |x_v - x_q| / sqrt(D) (sqrt(2 / 8) between
  // one-hot embeddings), then the same four values.
  const auto only = QesNodeFeatures(
      s, e, QesFeatureScaling::kNone, QesStructureFeatures::kReciprocalOnly);
  ASSERT_EQ(only.cols(), 1 + kQesReciprocalDim);
  EXPECT_NEAR(only(3, 0), 0.5f, 1e-6f);
  EXPECT_TRUE(only.rightCols(kQesReciprocalDim)
                  .isApprox(x.rightCols(kQesReciprocalDim)));
  // Query-scaled: sigma_q = RMS of x_v - x_q over the 1-hop nodes = 0.5.
  const auto scaled = QesNodeFeatures(s,
                                      e,
                                      QesFeatureScaling::kQueryScale,
                                      QesStructureFeatures::kReciprocalOnly);
  EXPECT_NEAR(scaled(3, 0), 1.f, 1e-6f);
}

TEST(QuerySubgraph, NodesOrderEdgesAndFeatures) {
  const QuerySubgraph s = HandBuiltSubgraph();
  // 1-hop: 1, 2. 2-hop from 1: (0 = query skipped), 4, (2 known); from 2: 5,
  // (0 skipped), 6.
  EXPECT_EQ(s.query, 0);
  EXPECT_EQ(s.num_one_hop, 2);
  EXPECT_EQ(s.nodes, (std::vector<int>{1, 2, 4, 5, 6}));
  // Edges from the u = 2 nearest: 1->4, 2->5, 4->1, 4->5, 5->2; 6's (7, 3)
  // are outside: node 6 is isolated.
  Eigen::MatrixXf expected = Eigen::MatrixXf::Zero(5, 5);
  auto edge = [&](int a, int b) { expected(a, b) = expected(b, a) = 1.f; };
  edge(0, 2);
  edge(1, 3);
  edge(2, 3);
  EXPECT_EQ(test::DenseAdjacency(s), expected);
  EXPECT_EQ(s.Degree(4), 0);

  // Symmetric aggregation.
  const Eigen::MatrixXf g =
      ComputeAggregation(s, GcnAggregation::kSymmetric).Dense();
  Eigen::MatrixXf g_expected = Eigen::MatrixXf::Zero(5, 5);
  const float r2 = 1.f / std::sqrt(2.f);
  g_expected(0, 2) = g_expected(2, 0) = r2;
  g_expected(1, 3) = g_expected(3, 1) = r2;
  g_expected(2, 3) = g_expected(3, 2) = 0.5f;
  EXPECT_TRUE(g.isApprox(g_expected, 1e-6f)) << g;

  // Row-normalised aggregation.
  const Eigen::MatrixXf gr =
      ComputeAggregation(s, GcnAggregation::kRowNormalized).Dense();
  Eigen::MatrixXf gr_expected = Eigen::MatrixXf::Zero(5, 5);
  gr_expected(0, 2) = 1.f;
  gr_expected(1, 3) = 1.f;
  gr_expected(2, 0) = gr_expected(2, 3) = 0.5f;
  gr_expected(3, 1) = gr_expected(3, 2) = 0.5f;
  EXPECT_TRUE(gr.isApprox(gr_expected, 1e-6f)) << gr;
  const std::vector<float> sums =
      ComputeAggregation(s, GcnAggregation::kRowNormalized).RowSums();
  EXPECT_EQ(sums, (std::vector<float>{1.f, 1.f, 1.f, 1.f, 0.f}));

  // Features x_v - x_q, and G X has a zero row for the isolated node.
  EmbeddingMatrix e(8, 2);
  for (int i = 0; i < 8; ++i) e.row(i) << i + 1.f, (i + 1.f) * (i + 1.f);
  const auto x = QesFeatures(s, e);
  ASSERT_EQ(x.rows(), 5);
  const int nodes[5] = {1, 2, 4, 5, 6};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(x(i, 0), nodes[i] + 1.f - 1.f);
    EXPECT_EQ(x(i, 1), (nodes[i] + 1.f) * (nodes[i] + 1.f) - 1.f);
  }
  const Eigen::MatrixXf gx = g * x;
  EXPECT_EQ(gx.row(4), Eigen::RowVector2f::Zero());
  EXPECT_FLOAT_EQ(gx(0, 0), r2 * x(2, 0));
}

TEST(QuerySubgraph, QueryScaledFeaturesHaveUnitRmsOverOneHopNodes) {
  const KnnGraph knn = HandBuiltKnn();
  const QuerySubgraph s = BuildQuerySubgraph(knn, 0, QesOptions{2, 3, 2});
  EmbeddingMatrix e(8, 2);
  for (int i = 0; i < 8; ++i) e.row(i) << i + 1.f, (i + 1.f) * (i + 1.f);
  // 1-hop nodes 1, 2: x = (1, 3), (2, 8); mean square over 2 x 2 values.
  const float factor = QesFeatureFactor(s, e, QesFeatureScaling::kQueryScale);
  EXPECT_FLOAT_EQ(factor, 1.f / std::sqrt((1.f + 9.f + 4.f + 64.f) / 4.f));
  EXPECT_EQ(QesFeatureFactor(s, e, QesFeatureScaling::kNone), 1.f);
  const auto raw = QesFeatures(s, e);
  const auto scaled = QesFeatures(s, e, QesFeatureScaling::kQueryScale);
  EXPECT_TRUE(scaled.isApprox(raw * factor, 1e-6f));
  EXPECT_NEAR(scaled.topRows(2).squaredNorm() / 4.0, 1.0, 1e-6);
  // The same collection scaled by 10: the same features (scale-free).
  const EmbeddingMatrix e10 = e * 10.f;
  EXPECT_TRUE(QesFeatures(s, e10, QesFeatureScaling::kQueryScale)
                  .isApprox(scaled, 1e-5f));
  // 1-hop nodes equal to the query: no division by zero.
  const EmbeddingMatrix same = EmbeddingMatrix::Ones(8, 2);
  EXPECT_EQ(QesFeatureFactor(s, same, QesFeatureScaling::kQueryScale), 1.f);
  EXPECT_STREQ(QesFeatureScalingName(QesFeatureScaling::kQueryScale), "query");
}

TEST(QuerySubgraph, QueryNeverANodeAndBuilderReusable) {
  const KnnGraph knn = HandBuiltKnn();
  QesOptions options;
  options.k1 = 3;
  options.k2 = 3;
  options.u = 3;
  QesBuilder builder(knn, options);
  QuerySubgraph s;
  for (int round = 0; round < 2; ++round) {
    for (int q = 0; q < 8; ++q) {
      builder.Build(q, &s);
      EXPECT_EQ(s.num_one_hop, 3);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(s.nodes[i], knn.indices(q, i));
      for (int node : s.nodes) EXPECT_NE(node, q);
      const Eigen::MatrixXf a = test::DenseAdjacency(s);
      EXPECT_EQ(a, a.transpose());
      EXPECT_EQ(a.diagonal().sum(), 0.f);
      EXPECT_EQ(BuildQuerySubgraph(knn, q, options).nodes, s.nodes);
    }
  }
}

TEST(QuerySubgraph, RejectsTooSmallGraphAndBadOptions) {
  const KnnGraph knn = HandBuiltKnn();
  QesOptions options;
  options.k1 = 4;
  options.k2 = 1;
  options.u = 1;
  EXPECT_THROW(QesBuilder(knn, options), Error);
  options.k1 = 2;
  options.u = 5;
  EXPECT_THROW(QesBuilder(knn, options), Error);
  options.u = 1;
  options.k1 = 0;
  EXPECT_THROW(options.Check(), OptionError);
  EXPECT_THROW(QesBuilder(knn, options), Error);
  EXPECT_EQ((QesOptions{100, 5, 10}.RequiredK()), 100);
}

}  // namespace
}  // namespace colmap_gcn

#include "training/distance_prior.h"

#include <gtest/gtest.h>

#include "gcn/gcn_test_utils.h"
#include "training/gcn_network.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

TEST(DistancePrior, NetworkComputesContextDistance) {
  // D = 8, layer 1 of 2 D = 16 units, four graph convolutions.
  GcnShape shape;
  shape.input_dim = 8;
  shape.gcn_dims = {16, 12, 8, 8};
  shape.fc_dim = 6;
  GcnModel model = InitializeGcnModel(shape, GcnAggregation::kRowNormalized, 3);
  InitializeDistancePrior(&model, 0.1f);
  std::vector<int> clusters;
  const EmbeddingMatrix embeddings =
      test::ClusteredEmbeddings({6, 5, 7}, 8, 0.3f, 4, &clusters);
  const KnnGraph knn = test::BruteForceKnn(embeddings, 10);
  for (const int q : {0, 7, 15}) {
    const QuerySubgraph subgraph = BuildQuerySubgraph(knn, q, {6, 3, 3});
    const GcnGraph<float> graph = MakeGcnGraph(model, subgraph, embeddings);
    const Eigen::MatrixXf g = graph.aggregation.Dense();
    // d = mean |x_v - x_q| over the dimensions; expected logit
    // -(d + G d + G^2 d + G^3 d).
    Eigen::VectorXf d = graph.features.cwiseAbs().rowwise().mean();
    Eigen::VectorXf expected = d;
    Eigen::VectorXf hop = d;
    for (int h = 1; h < 4; ++h) {
      hop = g * hop;
      expected += hop;
    }
    const ColVector<float> logits = GcnForwardReference(model.params, graph);
    ASSERT_EQ(logits.size(), subgraph.num_one_hop);
    for (int i = 0; i < subgraph.num_one_hop; ++i) {
      EXPECT_NEAR(logits(i), -expected(i), 1e-4f)
          << "query " << q << " node " << i;
    }
  }
  // Too narrow a first layer for 2 D units.
  shape.gcn_dims = {12, 12, 8, 8};
  GcnModel narrow =
      InitializeGcnModel(shape, GcnAggregation::kRowNormalized, 3);
  EXPECT_THROW(InitializeDistancePrior(&narrow, 0.1f), Error);
}

}  // namespace
}  // namespace colmap_gcn

#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "retrieval/knn.h"
#include "util/option_check.h"

namespace colmap_gcn {

// Query Enclosing Subgraph (QES) parameters, paper Sec. 3.2.
struct QesOptions {
  // 1-hop neighbours of the query (the candidates that get classified).
  int k1 = 100;
  // Neighbours added for every 1-hop node (2-hop nodes).
  int k2 = 5;
  // Edges: every node links to those of its u nearest neighbours in the whole
  // collection that lie in the subgraph.
  int u = 5;

  // Throws OptionError naming the first invalid field.
  void Check() const;
  // Largest neighbour count the kNN graph must provide: max(k1, k2, u).
  int RequiredK() const;
};

// How the adjacency A of a QES is normalised into the aggregation matrix G.
enum class GcnAggregation : int {
  // G = L^-1/2 A L^-1/2 with L = diag(row sums of A): the paper's Sec. 3.3.
  kSymmetric = 0,
  // G = L^-1 A (mean over neighbours): what gcn_clustering implements.
  kRowNormalized = 1,
};

const char* GcnAggregationName(GcnAggregation aggregation);
// "symmetric", "row": the names of --GcnTraining.aggregation.
const EnumNames<GcnAggregation>& GcnAggregationNames();

// How the QES node features x_v - x_q are scaled before the network.
enum class QesFeatureScaling : int {
  // As they are (paper Eq. 2).
  kNone = 0,
  // Divided by the query's own neighbourhood scale sigma_q, the RMS over
  // its 1-hop nodes and dimensions of x_v - x_q. Absolute embedding
  // distances differ between collections (renders and photos, objects and
  // streets) by more than the gap between matchable and unrelated
  // neighbours; relative ones travel.
  kQueryScale = 1,
};

const char* QesFeatureScalingName(QesFeatureScaling scaling);
// "none", "query": the names of --GcnTraining.feature_scaling.
const EnumNames<QesFeatureScaling>& QesFeatureScalingNames();

// Scale-free structural node features that a QES can add to the embedding
// differences: how the node and the query see each other in the kNN graph.
// Ranks and neighbour overlaps mean the same in every collection, whatever
// its embedding distances (the k-reciprocal evidence of re-ranking in
// image retrieval).
enum class QesStructureFeatures : int {
  kNone = 0,
  // Per node v of query q, kQesReciprocalDim values in [0, 1]:
  //   log(1 + r(q -> v)) / log(1 + K), r(q -> v) the rank of v in q's kNN
  //     list (0 = nearest; K when absent), K the kNN graph's K;
  //   log(1 + r(v -> q)) / log(1 + K), the same seen from v;
  //   Jaccard overlap of {q} + 5 nearest of q and {v} + 5 nearest of v;
  //   the same with the 10 nearest (both capped at K).
  kReciprocal = 1,
  // Only scale-free numbers, without x_v - x_q: the node's distance to the
  // query |c (x_v - x_q)| / sqrt(D) (c the QesFeatureFactor), then the
  // kReciprocal values. Nothing is left that a network could fit to one
  // collection's embedding directions.
  kReciprocalOnly = 2,
};

constexpr int kQesReciprocalDim = 4;

const char* QesStructureFeaturesName(QesStructureFeatures features);
// "none", "reciprocal", "reciprocal_only": the names of
// --GcnTraining.structure_features.
const EnumNames<QesStructureFeatures>& QesStructureFeaturesNames();
// Number of structural values per node: 0, kQesReciprocalDim or one more.
int QesStructureDim(QesStructureFeatures features);
// Whether the node features start with x_v - x_q (all but kReciprocalOnly).
bool QesUsesEmbeddingDifferences(QesStructureFeatures features);

// The nodes and undirected edges of one QES. Nodes are collection indices;
// nodes[0, num_one_hop) are the 1-hop nodes in kNN order, the rest the 2-hop
// nodes in discovery order (1-hop node by 1-hop node, each in kNN order).
// The query itself is never a node. The adjacency is symmetric, without self
// loops, stored as sorted neighbour lists (CSR over local node indices).
struct QuerySubgraph {
  int query = -1;
  int num_one_hop = 0;
  std::vector<int> nodes;
  std::vector<int> adjacency_offsets;  // size NumNodes() + 1
  std::vector<int> adjacency;          // local node indices
  // NumNodes() x kQesReciprocalDim, row-major: the kReciprocal values of
  // every node; filled by QesBuilder::Build only for a builder made with
  // structural features, empty otherwise.
  std::vector<float> reciprocal;

  int NumNodes() const { return static_cast<int>(nodes.size()); }
  int Degree(int local) const {
    return adjacency_offsets[local + 1] - adjacency_offsets[local];
  }
};

// Sparse aggregation matrix G (CSR, same pattern as the adjacency). Isolated
// nodes (degree 0) have an all-zero row and column, so their aggregated
// feature (G X)_i is 0.
struct AggregationMatrix {
  int num_nodes = 0;
  std::vector<int> offsets;  // size num_nodes + 1
  std::vector<int> columns;
  std::vector<float> values;

  // G 1: row sums (1 or 0 for row-normalised G).
  std::vector<float> RowSums() const;
  Eigen::MatrixXf Dense() const;
};

AggregationMatrix ComputeAggregation(const QuerySubgraph& subgraph,
                                     GcnAggregation aggregation);

// Builds QESs over one kNN graph. Keeps an O(N) scratch index map, so reuse
// one builder per thread for many queries.
class QesBuilder {
 public:
  // The kNN graph must outlive the builder and have K() >= RequiredK().
  // `structure`: the structural node features the subgraphs must carry
  // (QuerySubgraph::reciprocal); none skips their cost.
  QesBuilder(const KnnGraph& knn,
             const QesOptions& options,
             QesStructureFeatures structure = QesStructureFeatures::kNone);

  void Build(int query, QuerySubgraph* subgraph);

 private:
  void ComputeReciprocalFeatures(QuerySubgraph* subgraph);

  const KnnGraph& knn_;
  const QesOptions options_;
  const bool reciprocal_;
  std::vector<int> local_index_;  // collection index -> local index or -1
  std::vector<int> near_query_;   // collection index -> overlap set flags
};

QuerySubgraph BuildQuerySubgraph(
    const KnnGraph& knn,
    int query,
    const QesOptions& options,
    QesStructureFeatures structure = QesStructureFeatures::kNone);

// kNN graph for a QES over a collection of n images: k = min(RequiredK, n-1).
KnnGraph ComputeKnnForQes(const EmbeddingMatrix& embeddings,
                          const QesOptions& qes,
                          int num_threads);

// qes with k1, k2, u capped at n - 1.
QesOptions CapQesOptions(const QesOptions& qes, int num_images);

// Node features of a QES, paper Eq. 2: row i = e(nodes[i]) - e(query),
// times QesFeatureFactor.
Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
QesFeatures(const QuerySubgraph& subgraph,
            const EmbeddingMatrix& embeddings,
            QesFeatureScaling scaling = QesFeatureScaling::kNone);

// The QesStructureDim(structure) structural values of every node (rows).
Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
QesStructureValues(const QuerySubgraph& subgraph,
                   const EmbeddingMatrix& embeddings,
                   QesFeatureScaling scaling,
                   QesStructureFeatures structure);

// The network's raw node features: QesFeatures (unless kReciprocalOnly),
// followed by the QesStructureValues.
Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
QesNodeFeatures(const QuerySubgraph& subgraph,
                const EmbeddingMatrix& embeddings,
                QesFeatureScaling scaling,
                QesStructureFeatures structure);

// The factor every node feature of the QES is multiplied by: 1, or
// 1 / sigma_q (1 when the 1-hop nodes coincide with the query).
float QesFeatureFactor(const QuerySubgraph& subgraph,
                       const EmbeddingMatrix& embeddings,
                       QesFeatureScaling scaling);

}  // namespace colmap_gcn

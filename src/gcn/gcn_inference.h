#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "gcn/gcn_model.h"
#include "gcn/query_enclosing_subgraph.h"
#include "math/sgemm.h"
#include "retrieval/knn.h"

namespace colmap_gcn {

// Scratch buffers of one inference thread.
struct GcnWorkspace {
  std::vector<float> a;
  std::vector<float> b;
  std::vector<float> cat;
  std::vector<float> row_sums;
};

// The optimised test-time forward pass over one collection.
//  * Layer 1 is folded for the embedding part of the node features (the
//    few structural features are added per node): with
//    X = (E_V - 1 e_q^T - 1 m^T) diag(s),
//      [X || G X] W1 = P_a[V] - 1 (p_a(q) + c_a) + G P_b[V] - (G 1)(p_b(q) +
//      c_b)
//    where [P_a | P_b] = (E diag(s)) [W1_self | W1_agg] is computed ONCE for
//    all N images (memory N x 2 h1 floats) and c = (m .* s)^T W1.
//  * Layers 2..L-1 run on all nodes (their outputs reach the 1-hop nodes);
//    the last GCN layer and the FC layers run on the 1-hop rows only.
//  * GEMMs use the packed AVX-512/AVX2 kernel (gcn/sgemm.h) with the
//    weights of layers 2..L and FC1 packed once, not once per query.
class GcnScorer {
 public:
  // Both must outlive the scorer. Throws Error on a dimension mismatch.
  GcnScorer(const GcnModel& model,
            const EmbeddingMatrix& embeddings,
            int num_threads = -1);

  // Logits of the 1-hop nodes of one QES (size subgraph.num_one_hop).
  void ScoreSubgraph(const QuerySubgraph& subgraph,
                     GcnWorkspace* workspace,
                     std::vector<float>* logits) const;

  const GcnModel& Model() const { return model_; }

 private:
  // Writes b1 + [X || G X] W1_embedding, from the folded projections, into
  // the first `rows` rows of layer 1's pre-activations h (rows x h1).
  void WriteEmbeddingTerms(const QuerySubgraph& subgraph,
                           const AggregationMatrix& g,
                           int rows,
                           float* h) const;
  // Adds [S || G S] W1_structure to the first `rows` rows of h.
  void AddStructureTerms(const QuerySubgraph& subgraph,
                         const AggregationMatrix& g,
                         int rows,
                         float* h) const;

  const GcnModel& model_;
  const EmbeddingMatrix& embeddings_;
  RowMatrix<float> projected_;         // N x 2 h1: [P_a | P_b]; empty without D
  Eigen::VectorXf offset_;             // 2 h1: c = (m .* s)^T W1
  RowMatrix<float> structure_weight_;  // extra x 2 h1
  std::vector<PackedMatrix> packed_gcn_weights_;  // layers 2..L
  PackedMatrix packed_fc1_weight_;
};

// Matchability probabilities sigmoid(logit) of every query's 1-hop nodes:
// result[q][i] belongs to image knn.indices(q, i), i < min(k1, K). Builds the
// QESs with `qes` (knn.K() >= qes.RequiredK()). Deterministic for any number
// of threads.
std::vector<std::vector<float>> ScoreAllQueries(
    const GcnModel& model,
    const EmbeddingMatrix& embeddings,
    const KnnGraph& knn,
    const QesOptions& qes,
    int num_threads);

}  // namespace colmap_gcn

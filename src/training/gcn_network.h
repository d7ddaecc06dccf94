#pragma once

#include <vector>

#include "gcn/gcn_model.h"
#include "gcn/query_enclosing_subgraph.h"

namespace colmap_gcn {

// One QES ready for the network: standardised node features (n x D), the
// aggregation matrix G and the 1-hop count; labels (1 = matchable) for the
// 1-hop nodes when training.
template <typename T>
struct GcnGraph {
  RowMatrix<T> features;
  AggregationMatrix aggregation;
  int num_one_hop = 0;
  std::vector<uint8_t> labels;  // size num_one_hop (training only)
};

// Builds the network input of one QES with the model's standardisation and
// aggregation type.
GcnGraph<float> MakeGcnGraph(const GcnModel& model,
                             const QuerySubgraph& subgraph,
                             const EmbeddingMatrix& embeddings);

// The straightforward forward pass, exactly as written in the paper: dense G,
// every layer on every node, [X || G X] W + b; returns the logits of the
// 1-hop nodes. Used by tests as the reference for the optimised paths.
template <typename T>
ColVector<T> GcnForwardReference(const GcnParameters<T>& params,
                                 const GcnGraph<T>& graph);

// Binary cross-entropy with logits on the 1-hop nodes:
//   loss_i = w_i * (softplus(z_i) - y_i z_i),  w_i = positive_weight if y_i
// else 1 (torch's BCEWithLogitsLoss with pos_weight). Returns the SUM of
// loss_i over the 1-hop nodes and ADDS d(sum)/d(params) to *gradient (if not
// null). The last GCN layer and the FC layers run on the 1-hop rows only.
// Logits are written to *logits if not null.
template <typename T>
T GcnLossAndGradient(const GcnParameters<T>& params,
                     const GcnGraph<T>& graph,
                     T positive_weight,
                     GcnParameters<T>* gradient,
                     ColVector<T>* logits);

template <typename T>
GcnGraph<T> CastGraph(const GcnGraph<float>& graph) {
  GcnGraph<T> out;
  out.features = graph.features.template cast<T>();
  out.aggregation = graph.aggregation;
  out.num_one_hop = graph.num_one_hop;
  out.labels = graph.labels;
  return out;
}

}  // namespace colmap_gcn

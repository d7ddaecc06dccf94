#pragma once

#include "retrieval/knn.h"

namespace colmap_gcn {

// What both kNN methods start from: checks the options and the input
// (throws Error on non-finite values) and returns the N x k graph to fill,
// k = options.k capped at N - 1.
KnnGraph AllocateKnnGraph(const EmbeddingMatrix& embeddings,
                          const KnnOptions& options);

}  // namespace colmap_gcn

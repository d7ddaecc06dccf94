#pragma once

#include <cstdint>
#include <vector>

#include "gcn/gcn_model.h"
#include "gcn/query_enclosing_subgraph.h"
#include "retrieval/knn.h"

namespace colmap_gcn {
namespace test {

// Brute-force kNN with the KnnGraph conventions (self excluded, decreasing
// similarity, ties by increasing index).
KnnGraph BruteForceKnn(const EmbeddingMatrix& embeddings, int k);

// Unit vectors in `num_clusters` clusters of the given sizes: centre +
// noise * gaussian, normalised. cluster_of[i] is image i's cluster.
EmbeddingMatrix ClusteredEmbeddings(const std::vector<int>& cluster_sizes,
                                    int dim,
                                    float noise,
                                    uint32_t seed,
                                    std::vector<int>* cluster_of);

// Small network shape for fast tests.
GcnShape SmallShape(int input_dim);

// The subgraph's dense 0/1 adjacency (local node indices).
Eigen::MatrixXf DenseAdjacency(const QuerySubgraph& subgraph);

// Fills all parameters (and the input standardisation) with random values.
void RandomizeModel(GcnModel* model, uint32_t seed);

}  // namespace test
}  // namespace colmap_gcn

#pragma once

#include <cstdint>

#include <Eigen/Core>

namespace colmap_gcn {

// Global image descriptors, one row per image, L2-normalised, so that the
// paper's distance (Eq. 1) is a monotone function of the dot product:
// ||a - b||^2 = 2 - 2 a.b.
typedef Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
    EmbeddingMatrix;

struct KnnOptions {
  // Neighbours per image (capped at N - 1).
  int k = 100;

  // Threads; -1 uses all cores. Results do not depend on it.
  int num_threads = -1;

  // Rows per GEMM block (memory ~ block_size x N floats per thread).
  int block_size = 1024;

  bool Check() const;
};

// The k nearest neighbours of every image, the image itself excluded (by
// index, so duplicate vectors still find each other). Row i lists neighbour
// indices by decreasing similarity; ties are broken by increasing index, so
// the graph is deterministic.
struct KnnGraph {
  Eigen::Matrix<int32_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
      indices;  // N x k
  Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
      similarities;  // N x k, dot products of the unit vectors

  int NumImages() const { return static_cast<int>(indices.rows()); }
  int K() const { return static_cast<int>(indices.cols()); }
};

// Exact kNN by blocked GEMM with per-row top-k selection; memory O(N k) plus
// one block per thread.
KnnGraph ComputeExactKnn(const EmbeddingMatrix& embeddings,
                         const KnnOptions& options);

}  // namespace colmap_gcn

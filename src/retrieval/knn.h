#pragma once

#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "util/option_check.h"

namespace colmap_gcn {

// Global image descriptors, one row per image, L2-normalised, so that the
// paper's distance (Eq. 1) is a monotone function of the dot product:
// ||a - b||^2 = 2 - 2 a.b.
typedef Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
    EmbeddingMatrix;

// The neighbour search (KnnOptions::method).
enum class KnnMethod {
  kExact,      // ComputeExactKnn
  kFaissHnsw,  // ComputeApproximateKnn, only built with FAISS
};
// "exact", "faiss_hnsw".
const EnumNames<KnnMethod>& KnnMethodNames();

struct KnnOptions {
  // Neighbours per image (capped at N - 1).
  int k = 100;

  // Threads; -1 uses all cores. Results do not depend on it.
  int num_threads = -1;

  // Rows per GEMM block. The exact search multiplies block pairs (only the
  // upper triangle, as similarities are symmetric), so memory is
  // ~ block_size x block_size floats per thread plus the N x k result.
  int block_size = 1024;

  // kExact (ComputeExactKnn) or kFaissHnsw (ComputeApproximateKnn, only
  // when built with FAISS; see FaissAvailable()). Used by ComputeKnn.
  KnnMethod method = KnnMethod::kExact;

  // HNSW graph degree and search breadth for method = "faiss_hnsw".
  int hnsw_m = 32;
  int hnsw_ef_search = 256;

  // Throws OptionError naming the first invalid field.
  void Check() const;
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

// True when this build has FAISS (method = "faiss_hnsw" works).
bool FaissAvailable();

// Approximate kNN with a FAISS HNSW index on inner products: same output
// contract (self excluded, rows sorted, ties by index) but neighbours may be
// missed and, with several threads, results may vary between runs. Throws
// Error when built without FAISS.
KnnGraph ComputeApproximateKnn(const EmbeddingMatrix& embeddings,
                               const KnnOptions& options);

// Dispatches on options.method.
KnnGraph ComputeKnn(const EmbeddingMatrix& embeddings,
                    const KnnOptions& options);

}  // namespace colmap_gcn

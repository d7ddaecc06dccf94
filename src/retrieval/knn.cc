#include "retrieval/knn.h"

#include <algorithm>
#include <limits>
#include <mutex>
#include <vector>

#include "math/dense_product.h"
#include "retrieval/knn_graph_init.h"
#include "util/error.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/threading.h"

namespace colmap_gcn {

const EnumNames<KnnMethod>& KnnMethodNames() {
  static const EnumNames<KnnMethod> names = {
      {"exact", KnnMethod::kExact}, {"faiss_hnsw", KnnMethod::kFaissHnsw}};
  return names;
}

void KnnOptions::Check() const {
  CHECK_OPTION_GE(k, 0);
  CHECK_OPTION_NUM_THREADS(num_threads);
  CHECK_OPTION_GE(block_size, 1);
  CHECK_OPTION_GE(hnsw_m, 2);
  CHECK_OPTION_GE(hnsw_ef_search, 1);
}

namespace {

struct Neighbor {
  float similarity;
  int32_t index;
};

// The total order of the output: higher similarity first, then lower index.
// Because it is total, the top-k set of any candidate multiset is unique, so
// the result does not depend on the order candidates arrive in (threads).
inline bool Better(const Neighbor& a, const Neighbor& b) {
  return a.similarity > b.similarity ||
         (a.similarity == b.similarity && a.index < b.index);
}

// Per-row bounded heaps with the worst kept neighbour at the top, stored flat
// (N x k) so memory is exactly O(N k).
class TopKHeaps {
 public:
  TopKHeaps(int num_rows, int k)
      : k_(k), heaps_(static_cast<size_t>(num_rows) * k), sizes_(num_rows, 0) {}

  // Similarity below which a candidate for row cannot enter its heap.
  float Threshold(int row) const {
    return sizes_[row] < k_ ? -std::numeric_limits<float>::infinity()
                            : heaps_[static_cast<size_t>(row) * k_].similarity;
  }

  void Push(int row, const Neighbor& candidate) {
    Neighbor* heap = heaps_.data() + static_cast<size_t>(row) * k_;
    int& size = sizes_[row];
    if (size < k_) {
      // Sift up.
      int child = size++;
      while (child > 0) {
        const int parent = (child - 1) / 2;
        if (!Better(heap[parent], candidate)) break;
        heap[child] = heap[parent];
        child = parent;
      }
      heap[child] = candidate;
      return;
    }
    if (!Better(candidate, heap[0])) {
      return;
    }
    // Replace the worst and sift down.
    int parent = 0;
    while (true) {
      int child = 2 * parent + 1;
      if (child >= k_) break;
      if (child + 1 < k_ && Better(heap[child], heap[child + 1])) ++child;
      if (!Better(candidate, heap[child])) break;
      heap[parent] = heap[child];
      parent = child;
    }
    heap[parent] = candidate;
  }

  // Sorted neighbours of row, best first.
  void Sorted(int row, Neighbor* out) const {
    const Neighbor* heap = heaps_.data() + static_cast<size_t>(row) * k_;
    std::copy(heap, heap + sizes_[row], out);
    std::sort(out, out + sizes_[row], Better);
  }

 private:
  int k_;
  std::vector<Neighbor> heaps_;
  std::vector<int> sizes_;
};

}  // namespace

KnnGraph AllocateKnnGraph(const EmbeddingMatrix& embeddings,
                          const KnnOptions& options) {
  options.Check();
  if (!embeddings.allFinite()) {
    ThrowError("kNN input has non-finite (NaN or infinite) values");
  }
  const int num_rows = static_cast<int>(embeddings.rows());
  const int k = std::max(0, std::min(options.k, num_rows - 1));
  KnnGraph graph;
  graph.indices.resize(num_rows, k);
  graph.similarities.resize(num_rows, k);
  return graph;
}

KnnGraph ComputeExactKnn(const EmbeddingMatrix& embeddings,
                         const KnnOptions& options) {
  KnnGraph graph = AllocateKnnGraph(embeddings, options);
  const int num_rows = graph.NumImages();
  const int dim = static_cast<int>(embeddings.cols());
  const int k = graph.K();
  if (k == 0) {
    return graph;
  }

  // Similarities are symmetric, so only block pairs (I, J) with J >= I are
  // multiplied and each product updates the rows of both blocks: half the
  // flops of the full N x N product. The block partition depends only on
  // block_size, never on the thread count, so every similarity is computed
  // by the same kernel call and the output is identical for any threads.
  const int block_size = std::min(options.block_size, num_rows);
  const int num_blocks = (num_rows + block_size - 1) / block_size;
  std::vector<std::pair<int, int>> tasks;
  for (int bi = 0; bi < num_blocks; ++bi) {
    for (int bj = bi; bj < num_blocks; ++bj) tasks.emplace_back(bi, bj);
  }
  const int num_threads = EffectiveNumThreads(options.num_threads);

  TopKHeaps heaps(num_rows, k);
  std::vector<std::mutex> block_mutexes(num_blocks);
  std::vector<std::vector<float>> products(
      std::min<int>(num_threads, tasks.size()));
  std::vector<std::vector<float>> thresholds(products.size());
  const float* data = embeddings.data();

  ProgressLogger progress(tasks.size(), "kNN", "blocks");
  ParallelFor(0,
              static_cast<int>(tasks.size()),
              num_threads,
              [&](int task, int thread) {
                const int bi = tasks[task].first;
                const int bj = tasks[task].second;
                const int i0 = bi * block_size;
                const int j0 = bj * block_size;
                const int mi = std::min(block_size, num_rows - i0);
                const int mj = std::min(block_size, num_rows - j0);
                std::vector<float>& s = products[thread];
                s.resize(static_cast<size_t>(mi) * mj);
                MultiplyABt(data + static_cast<size_t>(i0) * dim,
                            mi,
                            data + static_cast<size_t>(j0) * dim,
                            mj,
                            dim,
                            s.data());
                if (bi == bj) {
                  // One value per unordered pair, also within a block.
                  for (int r = 0; r < mi; ++r) {
                    for (int c = 0; c < r; ++c) {
                      s[static_cast<size_t>(r) * mj + c] =
                          s[static_cast<size_t>(c) * mj + r];
                    }
                  }
                }
                {
                  std::lock_guard<std::mutex> lock(block_mutexes[bi]);
                  for (int r = 0; r < mi; ++r) {
                    const int i = i0 + r;
                    const float* row = s.data() + static_cast<size_t>(r) * mj;
                    float threshold = heaps.Threshold(i);
                    for (int c = 0; c < mj; ++c) {
                      const int j = j0 + c;
                      if (row[c] < threshold || j == i) continue;
                      heaps.Push(i, {row[c], j});
                      threshold = heaps.Threshold(i);
                    }
                  }
                }
                if (bi != bj) {
                  // Column-wise update of block J's rows, scanning S row by
                  // row for cache locality with one threshold per column.
                  std::lock_guard<std::mutex> lock(block_mutexes[bj]);
                  std::vector<float>& threshold = thresholds[thread];
                  threshold.resize(mj);
                  for (int c = 0; c < mj; ++c) {
                    threshold[c] = heaps.Threshold(j0 + c);
                  }
                  for (int r = 0; r < mi; ++r) {
                    const float* row = s.data() + static_cast<size_t>(r) * mj;
                    for (int c = 0; c < mj; ++c) {
                      if (row[c] < threshold[c]) continue;
                      heaps.Push(j0 + c, {row[c], i0 + r});
                      threshold[c] = heaps.Threshold(j0 + c);
                    }
                  }
                }
                progress.Increment();
              });

  std::vector<Neighbor> sorted(k);
  for (int i = 0; i < num_rows; ++i) {
    heaps.Sorted(i, sorted.data());
    for (int n = 0; n < k; ++n) {
      graph.indices(i, n) = sorted[n].index;
      graph.similarities(i, n) = sorted[n].similarity;
    }
  }
  return graph;
}

#ifndef COLMAP_GCN_HAVE_FAISS
bool FaissAvailable() { return false; }

KnnGraph ComputeApproximateKnn(const EmbeddingMatrix&, const KnnOptions&) {
  ThrowError(
      "approximate kNN (faiss_hnsw) needs a build with FAISS "
      "(libfaiss-dev); use method exact");
}
#endif

KnnGraph ComputeKnn(const EmbeddingMatrix& embeddings,
                    const KnnOptions& options) {
  if (options.method == KnnMethod::kFaissHnsw) {
    return ComputeApproximateKnn(embeddings, options);
  }
  return ComputeExactKnn(embeddings, options);
}

}  // namespace colmap_gcn

// Approximate kNN through FAISS; compiled only when FAISS is found.
#include <faiss/IndexHNSW.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "retrieval/knn.h"
#include "retrieval/knn_graph_init.h"

namespace colmap_gcn {

bool FaissAvailable() { return true; }

KnnGraph ComputeApproximateKnn(const EmbeddingMatrix& embeddings,
                               const KnnOptions& options) {
  KnnGraph graph = AllocateKnnGraph(embeddings, options);
  const int num_rows = graph.NumImages();
  const int dim = static_cast<int>(embeddings.cols());
  const int k = graph.K();
  if (k == 0) {
    return graph;
  }
  faiss::IndexHNSWFlat index(dim, options.hnsw_m, faiss::METRIC_INNER_PRODUCT);
  index.add(num_rows, embeddings.data());
  // Ask for one more so the query itself (normally the top hit) can be
  // dropped by index.
  const int k_search = std::min(k + 1, num_rows);
  faiss::SearchParametersHNSW params;
  params.efSearch = std::max(options.hnsw_ef_search, k_search);
  std::vector<float> distances(static_cast<size_t>(num_rows) * k_search);
  std::vector<faiss::Index::idx_t> labels(distances.size());
  index.search(num_rows,
               embeddings.data(),
               k_search,
               distances.data(),
               labels.data(),
               &params);
  for (int i = 0; i < num_rows; ++i) {
    std::vector<std::pair<float, int32_t>> row;
    for (int n = 0; n < k_search; ++n) {
      const faiss::Index::idx_t label =
          labels[static_cast<size_t>(i) * k_search + n];
      if (label < 0 || label == i) continue;
      row.emplace_back(distances[static_cast<size_t>(i) * k_search + n],
                       static_cast<int32_t>(label));
    }
    std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) {
      return a.first > b.first || (a.first == b.first && a.second < b.second);
    });
    for (int n = 0; n < k; ++n) {
      // HNSW may return fewer than k valid hits on tiny or degenerate data.
      graph.indices(i, n) =
          n < static_cast<int>(row.size()) ? row[n].second : -1;
      graph.similarities(i, n) = n < static_cast<int>(row.size())
                                     ? row[n].first
                                     : -std::numeric_limits<float>::infinity();
    }
  }
  return graph;
}

}  // namespace colmap_gcn

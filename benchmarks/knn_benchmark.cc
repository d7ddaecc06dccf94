// Timings for the retrieval kernels (not a test; prints numbers):
//   knn_benchmark knn [N D K THREADS NAIVE_QUERIES]
//       exact kNN over synthetic clustered unit vectors, plus a naive
//       per-query implementation (matrix-vector product + partial sort) on
//       NAIVE_QUERIES queries, extrapolated to N, for the speed ratio.
//   knn_benchmark embed [NUM_FEATURES NUM_IMAGES]
//       VLAD embedding time per image (64 words, 256-D), single thread.
// Defaults: knn 100000 256 100 2 2000; embed 8000 50.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "math/dense_product.h"
#include "retrieval/knn.h"
#include "retrieval/vlad.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

// num_clusters well-separated centres, points = centre + noise, normalised:
// like global descriptors of many small scenes.
EmbeddingMatrix ClusteredEmbeddings(int n, int d, int num_clusters) {
  std::mt19937 rng(42);
  std::normal_distribution<float> normal;
  EmbeddingMatrix centres(num_clusters, d);
  for (int i = 0; i < centres.size(); ++i) centres.data()[i] = normal(rng);
  centres.rowwise().normalize();
  EmbeddingMatrix x(n, d);
  for (int i = 0; i < n; ++i) {
    const int c = static_cast<int>(rng() % num_clusters);
    for (int j = 0; j < d; ++j) x(i, j) = centres(c, j) + 0.08f * normal(rng);
  }
  x.rowwise().normalize();
  return x;
}

int Knn(int n, int d, int k, int threads, int naive_queries) {
  std::printf("kernel: %s\n", DenseProductKernelName());
  const EmbeddingMatrix x = ClusteredEmbeddings(n, d, std::max(1, n / 100));
  KnnOptions options;
  options.k = k;
  options.num_threads = threads;
  Timer timer;
  const KnnGraph graph = ComputeExactKnn(x, options);
  const double exact_seconds = timer.ElapsedSeconds();
  std::printf("exact kNN: N=%d D=%d k=%d threads=%d: %.2f s (%.1f us/query)\n",
              n,
              d,
              k,
              threads,
              exact_seconds,
              1e6 * exact_seconds / n);

  // Naive: one query at a time, all similarities, partial sort.
  naive_queries = std::min(naive_queries, n);
  if (naive_queries <= 0) return 0;
  timer.Restart();
  int mismatches = 0;
  std::vector<int> order;
  for (int q = 0; q < naive_queries; ++q) {
    const Eigen::VectorXf s = x * x.row(q).transpose();
    order.resize(n);
    std::iota(order.begin(), order.end(), 0);
    std::partial_sort(
        order.begin(), order.begin() + k + 1, order.end(), [&](int a, int b) {
          return s(a) > s(b) || (s(a) == s(b) && a < b);
        });
    order.erase(std::remove(order.begin(), order.begin() + k + 1, q),
                order.begin() + k + 1);
    for (int m = 0; m < k; ++m) {
      if (order[m] != graph.indices(q, m)) {
        if (mismatches < 3) {
          std::printf("q=%d rank %d: naive %d (%.8f) exact %d (%.8f)\n",
                      q,
                      m,
                      order[m],
                      s(order[m]),
                      graph.indices(q, m),
                      graph.similarities(q, m));
        }
        ++mismatches;
      }
    }
  }
  const double naive_seconds = timer.ElapsedSeconds();
  const double extrapolated = naive_seconds * n / naive_queries;
  std::printf(
      "naive per-query (1 thread): %d queries in %.2f s -> %.1f s "
      "extrapolated to N=%d; exact blocked is %.1fx faster (%.1fx per "
      "thread); rank mismatches vs exact: %d of %d (float rounding ties)\n",
      naive_queries,
      naive_seconds,
      extrapolated,
      n,
      extrapolated / exact_seconds,
      extrapolated / (exact_seconds * threads),
      mismatches,
      naive_queries * k);
  return 0;
}

int Embed(int num_features, int num_images) {
  std::printf("kernel: %s\n", DenseProductKernelName());
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> uniform(0, 1);
  FloatMatrix codebook(64, 128);
  for (int i = 0; i < codebook.size(); ++i) codebook.data()[i] = uniform(rng);
  codebook.rowwise().normalize();
  PcaWhitening pca;
  pca.mean = Eigen::RowVectorXf::Zero(64 * 128);
  pca.projection.resize(256, 64 * 128);
  for (int i = 0; i < pca.projection.size(); ++i) {
    pca.projection.data()[i] = uniform(rng) - 0.5f;
  }
  pca.eigenvalues = Eigen::VectorXf::Ones(256);
  const VladEmbedding model(codebook, pca);
  std::vector<FeatureDescriptors> images;
  for (int i = 0; i < num_images; ++i) {
    FeatureDescriptors d(num_features, 128);
    for (int j = 0; j < d.size(); ++j) d.data()[j] = rng() % 120;
    images.push_back(std::move(d));
  }
  Timer timer;
  float checksum = 0;
  for (const auto& d : images) checksum += model.Embed(d)(0);
  const double seconds = timer.ElapsedSeconds();
  std::printf(
      "VLAD embedding (64 words -> 256-D), %d features/image, 1 thread: "
      "%.2f ms/image over %d images (checksum %g)\n",
      num_features,
      1e3 * seconds / num_images,
      num_images,
      checksum);
  return 0;
}

}  // namespace
}  // namespace colmap_gcn

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "knn";
  auto arg = [&](int i, int fallback) {
    return argc > i ? std::atoi(argv[i]) : fallback;
  };
  if (mode == "knn") {
    return colmap_gcn::Knn(
        arg(2, 100000), arg(3, 256), arg(4, 100), arg(5, 2), arg(6, 2000));
  }
  if (mode == "embed") {
    return colmap_gcn::Embed(arg(2, 8000), arg(3, 50));
  }
  std::fprintf(stderr, "usage: knn_benchmark knn|embed [args]\n");
  return 1;
}

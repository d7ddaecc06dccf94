#include "gcn/gcn_test_utils.h"

#include <algorithm>
#include <numeric>
#include <random>

namespace colmap_gcn {
namespace test {

KnnGraph BruteForceKnn(const EmbeddingMatrix& embeddings, int k) {
  const int n = static_cast<int>(embeddings.rows());
  k = std::min(k, n - 1);
  KnnGraph knn;
  knn.indices.resize(n, k);
  knn.similarities.resize(n, k);
  const Eigen::MatrixXf sims = embeddings * embeddings.transpose();
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) {
    order.resize(n);
    std::iota(order.begin(), order.end(), 0);
    order.erase(order.begin() + i);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return sims(i, a) > sims(i, b);
    });
    for (int j = 0; j < k; ++j) {
      knn.indices(i, j) = order[j];
      knn.similarities(i, j) = sims(i, order[j]);
    }
  }
  return knn;
}

EmbeddingMatrix ClusteredEmbeddings(const std::vector<int>& cluster_sizes,
                                    int dim,
                                    float noise,
                                    uint32_t seed,
                                    std::vector<int>* cluster_of) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.f, 1.f);
  const int n = std::accumulate(cluster_sizes.begin(), cluster_sizes.end(), 0);
  EmbeddingMatrix e(n, dim);
  cluster_of->clear();
  int row = 0;
  for (size_t c = 0; c < cluster_sizes.size(); ++c) {
    Eigen::VectorXf centre(dim);
    for (int j = 0; j < dim; ++j) centre(j) = normal(rng);
    centre.normalize();
    for (int i = 0; i < cluster_sizes[c]; ++i, ++row) {
      for (int j = 0; j < dim; ++j) {
        e(row, j) = centre(j) + noise * normal(rng);
      }
      e.row(row).normalize();
      cluster_of->push_back(static_cast<int>(c));
    }
  }
  return e;
}

GcnShape SmallShape(int input_dim) {
  GcnShape shape;
  shape.input_dim = input_dim;
  shape.gcn_dims = {24, 20, 16, 12};
  shape.fc_dim = 10;
  return shape;
}

Eigen::MatrixXf DenseAdjacency(const QuerySubgraph& subgraph) {
  const int n = subgraph.NumNodes();
  Eigen::MatrixXf dense = Eigen::MatrixXf::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int e = subgraph.adjacency_offsets[i];
         e < subgraph.adjacency_offsets[i + 1];
         ++e) {
      dense(i, subgraph.adjacency[e]) = 1.f;
    }
  }
  return dense;
}

void RandomizeModel(GcnModel* model, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uniform(-0.5f, 0.5f);
  for (float& v : model->params.Values()) v = uniform(rng);
  for (int i = 0; i < model->shape.input_dim; ++i) {
    model->input_shift(i) = 0.1f * uniform(rng);
    model->input_scale(i) = 1.5f + uniform(rng);
  }
}

}  // namespace test
}  // namespace colmap_gcn

#pragma once

// Synthetic embeddings for the GCN benchmarks: images in clusters ("scenes
// or landmarks") of log-uniform size, centre + isotropic noise, normalised.

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "retrieval/knn.h"

namespace colmap_gcn {
namespace bench {

inline EmbeddingMatrix SyntheticEmbeddings(int num_images,
                                           int dim,
                                           uint32_t seed,
                                           std::vector<int>* cluster_of,
                                           int min_cluster = 5,
                                           int max_cluster = 300,
                                           float noise = 0.05f) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.f, 1.f);
  std::uniform_real_distribution<double> uniform(std::log(min_cluster),
                                                 std::log(max_cluster));
  EmbeddingMatrix e(num_images, dim);
  cluster_of->assign(num_images, 0);
  Eigen::VectorXf centre(dim);
  int cluster = -1;
  int remaining = 0;
  for (int i = 0; i < num_images; ++i) {
    if (remaining == 0) {
      ++cluster;
      remaining = static_cast<int>(std::lround(std::exp(uniform(rng))));
      for (int j = 0; j < dim; ++j) centre(j) = normal(rng);
      centre.normalize();
    }
    --remaining;
    for (int j = 0; j < dim; ++j) e(i, j) = centre(j) + noise * normal(rng);
    e.row(i).normalize();
    (*cluster_of)[i] = cluster;
  }
  return e;
}

}  // namespace bench
}  // namespace colmap_gcn

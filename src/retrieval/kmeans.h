#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace colmap_gcn {

typedef Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
    FloatMatrix;

struct KMeansOptions {
  // Number of centres (must be <= number of points).
  int num_clusters = 64;

  // Lloyd iterations at most; stops earlier when no assignment changes.
  int max_iterations = 25;

  // Seed of the k-means++ initialisation (std::mt19937).
  uint32_t seed = 0;

  // Threads for the assignment step; -1 uses all cores. The result does not
  // depend on it: assignments are per point and the centre sums are
  // accumulated sequentially in point order.
  int num_threads = -1;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// Index of the nearest centre of every row of points (squared L2; ties go to
// the lower centre index).
std::vector<int> AssignToNearestCenter(const FloatMatrix& points,
                                       const FloatMatrix& centers,
                                       int num_threads = 1);

// k-means with k-means++ initialisation; returns num_clusters x D centres.
// Deterministic for a seed. Empty clusters are re-seeded with the point
// farthest from its centre.
FloatMatrix KMeans(const FloatMatrix& points, const KMeansOptions& options);

}  // namespace colmap_gcn

#include "retrieval/kmeans.h"

#include <algorithm>
#include <limits>
#include <random>

#include "math/dense_product.h"
#include "retrieval/knn.h"
#include "util/error.h"
#include "util/option_check.h"
#include "util/threading.h"

namespace colmap_gcn {

void KMeansOptions::Check() const {
  CHECK_OPTION_GE(num_clusters, 1);
  CHECK_OPTION_GE(max_iterations, 0);
  CHECK_OPTION_NUM_THREADS(num_threads);
}

namespace {

// Fixed chunking: the partition of points never depends on the thread count.
const int kChunkSize = 4096;

template <typename Fn>
void ForEachChunk(int num_points, int num_threads, const Fn& fn) {
  const int num_chunks = (num_points + kChunkSize - 1) / kChunkSize;
  ParallelFor(0, num_chunks, num_threads, [&](int chunk) {
    const int begin = chunk * kChunkSize;
    fn(begin, std::min(num_points, begin + kChunkSize));
  });
}

// Assigns points to centres and returns each point's squared distance.
std::vector<int> Assign(const FloatMatrix& points,
                        const FloatMatrix& centers,
                        int num_threads,
                        std::vector<float>* distances) {
  const int num_points = static_cast<int>(points.rows());
  const int num_centers = static_cast<int>(centers.rows());
  const int dim = static_cast<int>(points.cols());
  const Eigen::VectorXf center_norms = centers.rowwise().squaredNorm();
  std::vector<int> assignment(num_points, 0);
  if (distances != nullptr) distances->assign(num_points, 0.f);
  ForEachChunk(num_points, num_threads, [&](int begin, int end) {
    std::vector<float> products(static_cast<size_t>(end - begin) * num_centers);
    MultiplyABt(points.data() + static_cast<size_t>(begin) * dim,
                end - begin,
                centers.data(),
                num_centers,
                dim,
                products.data());
    for (int i = begin; i < end; ++i) {
      const float* row =
          products.data() + static_cast<size_t>(i - begin) * num_centers;
      int best = 0;
      float best_value = std::numeric_limits<float>::infinity();
      for (int c = 0; c < num_centers; ++c) {
        const float value = center_norms(c) - 2.f * row[c];
        if (value < best_value) {
          best_value = value;
          best = c;
        }
      }
      assignment[i] = best;
      if (distances != nullptr) {
        (*distances)[i] =
            std::max(0.f, best_value + points.row(i).squaredNorm());
      }
    }
  });
  return assignment;
}

FloatMatrix KMeansPlusPlus(const FloatMatrix& points,
                           int num_clusters,
                           std::mt19937* rng) {
  const int num_points = static_cast<int>(points.rows());
  FloatMatrix centers(num_clusters, points.cols());
  std::vector<double> min_distances(num_points,
                                    std::numeric_limits<double>::infinity());
  int chosen = std::uniform_int_distribution<int>(0, num_points - 1)(*rng);
  for (int c = 0; c < num_clusters; ++c) {
    centers.row(c) = points.row(chosen);
    double total = 0;
    for (int i = 0; i < num_points; ++i) {
      const double distance = (points.row(i) - centers.row(c)).squaredNorm();
      min_distances[i] = std::min(min_distances[i], distance);
      total += min_distances[i];
    }
    if (c + 1 == num_clusters) break;
    if (total <= 0) {
      // All points coincide with chosen centres: any point will do.
      chosen = std::uniform_int_distribution<int>(0, num_points - 1)(*rng);
      continue;
    }
    // D^2 sampling by inverting the cumulative sum.
    const double target =
        std::uniform_real_distribution<double>(0, total)(*rng);
    double cumulative = 0;
    chosen = num_points - 1;
    for (int i = 0; i < num_points; ++i) {
      cumulative += min_distances[i];
      if (cumulative > target && min_distances[i] > 0) {
        chosen = i;
        break;
      }
    }
  }
  return centers;
}

}  // namespace

std::vector<int> AssignToNearestCenter(const FloatMatrix& points,
                                       const FloatMatrix& centers,
                                       int num_threads) {
  THROW_CHECK(points.cols() == centers.cols() && centers.rows() > 0);
  return Assign(points, centers, EffectiveNumThreads(num_threads), nullptr);
}

FloatMatrix KMeans(const FloatMatrix& points, const KMeansOptions& options) {
  options.Check();
  const int num_points = static_cast<int>(points.rows());
  const int dim = static_cast<int>(points.cols());
  const int num_clusters = options.num_clusters;
  if (num_points < num_clusters) {
    ThrowError(
        "k-means needs at least ", num_clusters, " points, got ", num_points);
  }
  const int num_threads = EffectiveNumThreads(options.num_threads);
  std::mt19937 rng(options.seed);
  FloatMatrix centers = KMeansPlusPlus(points, num_clusters, &rng);
  std::vector<int> assignment;
  std::vector<float> distances;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    std::vector<int> new_assignment =
        Assign(points, centers, num_threads, &distances);
    if (new_assignment == assignment) break;
    assignment.swap(new_assignment);
    // Sequential double sums in point order: deterministic.
    Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(num_clusters, dim);
    std::vector<int> counts(num_clusters, 0);
    for (int i = 0; i < num_points; ++i) {
      sums.row(assignment[i]) += points.row(i).cast<double>();
      ++counts[assignment[i]];
    }
    std::vector<bool> taken(num_points, false);
    for (int c = 0; c < num_clusters; ++c) {
      if (counts[c] > 0) {
        centers.row(c) = (sums.row(c) / counts[c]).cast<float>();
        continue;
      }
      // Re-seed an empty cluster at the worst-served point.
      int farthest = -1;
      for (int i = 0; i < num_points; ++i) {
        if (!taken[i] && (farthest < 0 || distances[i] > distances[farthest])) {
          farthest = i;
        }
      }
      taken[farthest] = true;
      centers.row(c) = points.row(farthest);
    }
  }
  return centers;
}

}  // namespace colmap_gcn

#include "verification/fundamental_ransac.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "util/option_check.h"
#include "util/random.h"

namespace colmap_gcn {
namespace {

constexpr int kSampleSize = 8;
constexpr int kNumRefits = 3;

// Hartley's normalisation: centroid at the origin, mean distance sqrt(2).
Eigen::Matrix3d NormalisingTransform(const Eigen::Matrix2Xd& points) {
  const Eigen::Vector2d centroid = points.rowwise().mean();
  const double mean_distance =
      (points.colwise() - centroid).colwise().norm().mean();
  const double scale = mean_distance > 0 ? std::sqrt(2.0) / mean_distance : 1;
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  T(0, 0) = scale;
  T(1, 1) = scale;
  T(0, 2) = -scale * centroid.x();
  T(1, 2) = -scale * centroid.y();
  return T;
}

// The least-squares F (rank 2) of the matches in `indices`, in normalised
// coordinates (x2' F x1 = 0 with xi = Ti pi); false when degenerate.
bool FitFundamental(const Eigen::Matrix3Xd& x1,
                    const Eigen::Matrix3Xd& x2,
                    const std::vector<int>& indices,
                    Eigen::Matrix3d* F) {
  Eigen::Matrix<double, 9, 9> AtA = Eigen::Matrix<double, 9, 9>::Zero();
  for (const int i : indices) {
    Eigen::Matrix<double, 9, 1> row;
    const Eigen::Vector3d& a = x1.col(i);
    const Eigen::Vector3d& b = x2.col(i);
    row << b(0) * a(0), b(0) * a(1), b(0), b(1) * a(0), b(1) * a(1), b(1), a(0),
        a(1), 1;
    AtA.noalias() += row * row.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> solver(AtA);
  if (solver.info() != Eigen::Success) return false;
  const Eigen::Matrix<double, 9, 1> f = solver.eigenvectors().col(0);
  Eigen::Matrix3d G;
  G << f(0), f(1), f(2), f(3), f(4), f(5), f(6), f(7), f(8);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(
      G, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d singular = svd.singularValues();
  if (!(singular(0) > 0) || !std::isfinite(singular(0))) return false;
  singular(2) = 0;
  *F = svd.matrixU() * singular.asDiagonal() * svd.matrixV().transpose();
  return true;
}

// Trials needed to draw an all-inlier sample with `confidence`.
int RequiredTrials(double inlier_ratio, double confidence, int max_trials) {
  const double all_inliers = std::pow(inlier_ratio, kSampleSize);
  if (all_inliers >= 1) return 1;
  if (all_inliers <= 0) return max_trials;
  const double trials =
      std::ceil(std::log(1 - confidence) / std::log(1 - all_inliers));
  if (!std::isfinite(trials) || trials > max_trials) return max_trials;
  return std::max(1, static_cast<int>(trials));
}

}  // namespace

void FundamentalRansacOptions::Check() const {
  CHECK_OPTION_GT(max_error, 0.0);
  CHECK_OPTION_INTERVAL(confidence, 0.0, false, 1.0, false);
  CHECK_OPTION_GE(max_num_trials, 1);
  CHECK_OPTION_INTERVAL(min_inlier_ratio, 0.0, false, 1.0, true);
}

double SquaredSampsonError(const Eigen::Matrix3d& F,
                           const Eigen::Vector2d& point1,
                           const Eigen::Vector2d& point2) {
  const Eigen::Vector3d x1 = point1.homogeneous();
  const Eigen::Vector3d x2 = point2.homogeneous();
  const Eigen::Vector3d Fx1 = F * x1;
  const Eigen::Vector3d Ftx2 = F.transpose() * x2;
  const double numerator = x2.dot(Fx1);
  const double denominator =
      Fx1(0) * Fx1(0) + Fx1(1) * Fx1(1) + Ftx2(0) * Ftx2(0) + Ftx2(1) * Ftx2(1);
  if (!(denominator > 0)) return std::numeric_limits<double>::infinity();
  return numerator * numerator / denominator;
}

FundamentalRansacResult EstimateFundamentalRansac(
    const Eigen::Matrix2Xd& points1,
    const Eigen::Matrix2Xd& points2,
    const FundamentalRansacOptions& options,
    const uint64_t seed) {
  options.Check();
  THROW_CHECK(points1.cols() == points2.cols());
  FundamentalRansacResult result;
  const int n = static_cast<int>(points1.cols());
  if (n < kSampleSize) return result;

  const Eigen::Matrix3d T1 = NormalisingTransform(points1);
  const Eigen::Matrix3d T2 = NormalisingTransform(points2);
  const Eigen::Matrix3Xd x1 = T1 * points1.colwise().homogeneous();
  const Eigen::Matrix3Xd x2 = T2 * points2.colwise().homogeneous();
  const double max_squared_error = options.max_error * options.max_error;

  // Inliers of a normalised-coordinate F, measured in pixels.
  auto count_inliers = [&](const Eigen::Matrix3d& F_normalised,
                           std::vector<int>* inliers) {
    const Eigen::Matrix3d F = T2.transpose() * F_normalised * T1;
    inliers->clear();
    for (int i = 0; i < n; ++i) {
      if (SquaredSampsonError(F, points1.col(i), points2.col(i)) <=
          max_squared_error) {
        inliers->push_back(i);
      }
    }
    return F;
  };

  const int max_trials = RequiredTrials(
      options.min_inlier_ratio, options.confidence, options.max_num_trials);
  int needed_trials = max_trials;
  uint64_t state = seed;
  std::vector<int> sample(kSampleSize);
  std::vector<int> inliers;
  for (int trial = 0; trial < needed_trials; ++trial) {
    ++result.num_trials;
    // Eight distinct indices (rejection sampling; n >= 8).
    for (int s = 0; s < kSampleSize; ++s) {
      while (true) {
        const int index = static_cast<int>(SplitMix64(&state) % n);
        if (std::find(sample.begin(), sample.begin() + s, index) ==
            sample.begin() + s) {
          sample[s] = index;
          break;
        }
      }
    }
    Eigen::Matrix3d F_normalised;
    if (!FitFundamental(x1, x2, sample, &F_normalised)) continue;
    const Eigen::Matrix3d F = count_inliers(F_normalised, &inliers);
    if (inliers.size() > result.inliers.size()) {
      result.success = true;
      result.F = F;
      result.inliers = inliers;
      needed_trials =
          std::min(max_trials,
                   RequiredTrials(static_cast<double>(inliers.size()) / n,
                                  options.confidence,
                                  max_trials));
    }
  }
  if (!result.success) return result;

  // Local optimisation: refit on the inliers while that keeps more.
  for (int refit = 0; refit < kNumRefits; ++refit) {
    if (static_cast<int>(result.inliers.size()) < kSampleSize) break;
    Eigen::Matrix3d F_normalised;
    if (!FitFundamental(x1, x2, result.inliers, &F_normalised)) break;
    const Eigen::Matrix3d F = count_inliers(F_normalised, &inliers);
    if (inliers.size() <= result.inliers.size()) break;
    result.F = F;
    result.inliers = inliers;
  }
  return result;
}

}  // namespace colmap_gcn

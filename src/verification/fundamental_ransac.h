#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace colmap_gcn {

// RANSAC for a fundamental matrix (normalised eight-point samples, Sampson
// error, then least-squares refits on the inliers) whose only randomness is
// a seed: the same points and seed give the same matrix and inliers on every
// machine. Defaults are COLMAP's --SiftMatching options.
struct FundamentalRansacOptions {
  // --SiftMatching.max_error: the largest Sampson distance of an inlier, in
  // pixels.
  double max_error = 4;
  // --SiftMatching.confidence: stop once an all-inlier sample has been drawn
  // with this probability.
  double confidence = 0.999;
  // --SiftMatching.max_num_trials.
  int max_num_trials = 10000;
  // --SiftMatching.min_inlier_ratio: the number of trials never exceeds what
  // this inlier ratio needs.
  double min_inlier_ratio = 0.25;

  void Check() const;
};

struct FundamentalRansacResult {
  bool success = false;
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();  // x2' F x1 = 0
  std::vector<int> inliers;                     // indices into the points
  int num_trials = 0;
};

// points1.col(i) and points2.col(i) are the pixel positions of match i.
FundamentalRansacResult EstimateFundamentalRansac(
    const Eigen::Matrix2Xd& points1,
    const Eigen::Matrix2Xd& points2,
    const FundamentalRansacOptions& options,
    uint64_t seed);

// The squared Sampson distance of a match under F.
double SquaredSampsonError(const Eigen::Matrix3d& F,
                           const Eigen::Vector2d& point1,
                           const Eigen::Vector2d& point2);

}  // namespace colmap_gcn

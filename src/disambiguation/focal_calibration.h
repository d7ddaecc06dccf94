#pragma once

#include <vector>

#include <Eigen/Core>

#include "disambiguation/relative_pose.h"

namespace colmap_gcn {

// Self-calibration of focal lengths from fundamental matrices (the
// essential-matrix consistency criterion, Mendonca & Cipolla 1999): with the
// right intrinsics, E = K2' F K1 has two equal singular values. Used by the
// look-alike filter when the database's focal lengths are COLMAP's guesses
// (no EXIF), whose rotations drift around rings (docs/lookalike.md).
struct FocalCalibrationOptions {
  // Range of the scale factors tried on a guessed focal length (log-spaced
  // grid, then refined around the best).
  double min_scale = 0.5;   // default 0.5
  double max_scale = 2.0;   // default 2
  int num_grid_steps = 61;  // default 61 (at least 7)

  // Fewer pairs touching a guessed camera (verified calibrated or
  // uncalibrated; planar and panoramic F are no evidence): no calibration.
  int min_num_pairs = 8;  // default 8

  // A camera gets its own focal length when it has at least this many
  // images and this many pairs; the other guessed cameras share one scale
  // factor.
  int min_images_per_camera = 2;  // default 2
  int min_pairs_per_camera = 10;  // default 10

  void Check() const;
};

// A verified pair's fundamental matrix (x2' F x1 = 0) between two cameras
// (indices into the camera list).
struct FundamentalPair {
  int camera1 = 0;
  int camera2 = 0;
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
};

// (s1 - s2) / (s1 + s2) of E's two largest singular values: 0 for an
// essential matrix, 1 for a degenerate one.
double EssentialInconsistency(const Eigen::Matrix3d& E);

struct FocalCalibrationResult {
  std::vector<PinholeIntrinsics> cameras;  // with the calibrated focals
  std::vector<double> scales;              // applied to each camera's focal
  // The guessed cameras whose focal length the criterion fixed (a minimum
  // inside the searched range); false for declined and trusted cameras.
  std::vector<bool> calibrated;
  double cost_before = 0;  // median inconsistency with the given focals
  double cost_after = 0;   // and with the calibrated ones
  int num_pairs = 0;       // pairs that touch a guessed camera
};

// Scales the focal lengths (fx and fy alike) of the cameras whose focal is
// not trusted (trusted[c] false) to minimise the median inconsistency of
// the pairs touching them; trusted cameras are kept. A scale whose minimum
// lies near an end of the searched range (within 8 grid steps, 13 % of
// the range) is declined (kept at 1): the criterion then has no minimum
// inside it.
// Deterministic.
FocalCalibrationResult SelfCalibrateFocalLengths(
    const std::vector<PinholeIntrinsics>& cameras,
    const std::vector<bool>& trusted,
    const std::vector<int>& num_images_per_camera,
    const std::vector<FundamentalPair>& pairs,
    const FocalCalibrationOptions& options);

}  // namespace colmap_gcn

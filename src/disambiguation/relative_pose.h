#pragma once

#include <vector>

#include <Eigen/Core>

#include "scene/database.h"

namespace colmap_gcn {

// Pinhole intrinsics (focal lengths and principal point) of a COLMAP camera,
// ignoring distortion: enough to turn a fundamental matrix into an
// essential one and pixels into rays for the cheirality test.
struct PinholeIntrinsics {
  double fx = 1;
  double fy = 1;
  double cx = 0;
  double cy = 0;

  Eigen::Matrix3d K() const;
};

// Throws Error on an unknown model or too few parameters.
PinholeIntrinsics IntrinsicsOfCamera(const DatabaseCamera& camera);

// The rotation R of x2 = R x1 + t (camera 2's frame from camera 1's) from an
// essential matrix (x2' E x1 = 0) and matched rays (normalised image
// coordinates, one column each), choosing among E's four decompositions the
// one that puts most points in front of both cameras. Returns false when E is
// degenerate or no decomposition puts at least half of the points in front.
bool RotationFromEssential(const Eigen::Matrix3d& E,
                           const Eigen::Matrix2Xd& rays1,
                           const Eigen::Matrix2Xd& rays2,
                           Eigen::Matrix3d* rotation);

// The rotations R of x2 = R x1 + t that a homography between normalised
// coordinates (x2 ~ H x1, H = R + t n' / d for a plane n' X = d) allows:
// its decompositions (the SVD method of Faugeras & Lustman) that put at
// least half of the rays in front of both cameras and at least 90 % as many
// as the best one; one rotation when H is a pure rotation (equal singular
// values). Empty when H is degenerate or no decomposition qualifies.
std::vector<Eigen::Matrix3d> RotationsFromHomography(
    const Eigen::Matrix3d& H,
    const Eigen::Matrix2Xd& rays1,
    const Eigen::Matrix2Xd& rays2);

// Angle of a rotation matrix in degrees, in [0, 180].
double RotationAngleDegrees(const Eigen::Matrix3d& rotation);

}  // namespace colmap_gcn

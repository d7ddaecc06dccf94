#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace colmap_gcn {

// A pinhole camera in COLMAP's conventions: world-to-camera rotation R and
// translation t (x_cam = R * X + t), camera x right, y down, z forward, and
// image coordinates in which the centre of pixel (0, 0) is at (0.5, 0.5).
struct PinholeCamera {
  int width = 0;
  int height = 0;
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  Eigen::Vector3d Center() const { return -R.transpose() * t; }

  // World point to camera coordinates.
  Eigen::Vector3d ToCamera(const Eigen::Vector3d& X) const { return R * X + t; }

  // Projects a world point; returns false if it lies behind the camera
  // (z <= min_depth). Does not check the image bounds.
  bool Project(const Eigen::Vector3d& X,
               Eigen::Vector2d* xy,
               double min_depth = 1e-6) const;

  bool IsInImage(const Eigen::Vector2d& xy) const {
    return xy.x() >= 0.0 && xy.y() >= 0.0 && xy.x() < width && xy.y() < height;
  }

  // Unit world-space direction of the ray through image coordinate (x, y).
  Eigen::Vector3d RayDirection(double x, double y) const;

  // COLMAP quaternion (w, x, y, z) of R, with w >= 0.
  Eigen::Vector4d Qvec() const;
};

// Camera at `center` looking at `target`, world up +z, rotated by `roll`
// radians about its viewing direction.
PinholeCamera LookAtCamera(const Eigen::Vector3d& center,
                           const Eigen::Vector3d& target,
                           double roll,
                           int width,
                           int height,
                           double focal_length);

}  // namespace colmap_gcn

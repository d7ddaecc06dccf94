#include "synthetic/camera.h"

#include <cmath>

namespace colmap_gcn {

bool PinholeCamera::Project(const Eigen::Vector3d& X,
                            Eigen::Vector2d* xy,
                            double min_depth) const {
  const Eigen::Vector3d p = ToCamera(X);
  if (p.z() <= min_depth) {
    return false;
  }
  *xy = Eigen::Vector2d(fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy);
  return true;
}

Eigen::Vector3d PinholeCamera::RayDirection(double x, double y) const {
  const Eigen::Vector3d d((x - cx) / fx, (y - cy) / fy, 1.0);
  return (R.transpose() * d).normalized();
}

Eigen::Vector4d PinholeCamera::Qvec() const {
  Eigen::Quaterniond q(R);
  q.normalize();
  Eigen::Vector4d qvec(q.w(), q.x(), q.y(), q.z());
  if (qvec(0) < 0.0) {
    qvec = -qvec;
  }
  return qvec;
}

PinholeCamera LookAtCamera(const Eigen::Vector3d& center,
                           const Eigen::Vector3d& target,
                           double roll,
                           int width,
                           int height,
                           double focal_length) {
  const Eigen::Vector3d forward = (target - center).normalized();
  Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ());
  if (right.norm() < 1e-9) {
    right = Eigen::Vector3d::UnitX();
  }
  right.normalize();
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix3d R;
  R.row(0) = right.transpose();
  R.row(1) = down.transpose();
  R.row(2) = forward.transpose();
  // Roll about the camera z axis.
  const Eigen::Matrix3d roll_rotation =
      Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  R = roll_rotation * R;

  PinholeCamera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = focal_length;
  camera.fy = focal_length;
  camera.cx = 0.5 * width;
  camera.cy = 0.5 * height;
  camera.R = R;
  camera.t = -R * center;
  return camera;
}

}  // namespace colmap_gcn

#include "disambiguation/relative_pose.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "util/error.h"

namespace colmap_gcn {
namespace {

// Depths of a ray pair triangulated (linear, DLT) with P1 = [I | 0] and
// P2 = [R | t]; both must be positive for the point to lie in front.
bool InFrontOfBoth(const Eigen::Matrix3d& R,
                   const Eigen::Vector3d& t,
                   const Eigen::Vector2d& x1,
                   const Eigen::Vector2d& x2) {
  Eigen::Matrix<double, 3, 4> P1 = Eigen::Matrix<double, 3, 4>::Zero();
  P1.leftCols<3>() = Eigen::Matrix3d::Identity();
  Eigen::Matrix<double, 3, 4> P2;
  P2.leftCols<3>() = R;
  P2.col(3) = t;
  Eigen::Matrix4d A;
  A.row(0) = x1.x() * P1.row(2) - P1.row(0);
  A.row(1) = x1.y() * P1.row(2) - P1.row(1);
  A.row(2) = x2.x() * P2.row(2) - P2.row(0);
  A.row(3) = x2.y() * P2.row(2) - P2.row(1);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (std::abs(X(3)) < 1e-12) return false;
  const Eigen::Vector3d point = X.head<3>() / X(3);
  return point.z() > 0 && (R * point + t).z() > 0;
}

}  // namespace

Eigen::Matrix3d PinholeIntrinsics::K() const {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  K(0, 0) = fx;
  K(1, 1) = fy;
  K(0, 2) = cx;
  K(1, 2) = cy;
  return K;
}

PinholeIntrinsics IntrinsicsOfCamera(const DatabaseCamera& camera) {
  // COLMAP 3.8's model ids: one focal length (SIMPLE_PINHOLE, SIMPLE_RADIAL,
  // RADIAL, SIMPLE_RADIAL_FISHEYE, RADIAL_FISHEYE: f, cx, cy, ...) or two
  // (PINHOLE, OPENCV, OPENCV_FISHEYE, FULL_OPENCV, FOV,
  // THIN_PRISM_FISHEYE: fx, fy, cx, cy, ...).
  const std::vector<double>& p = camera.params;
  PinholeIntrinsics intrinsics;
  switch (camera.model_id) {
    case 0:
    case 2:
    case 3:
    case 8:
    case 9:
      if (p.size() < 3) break;
      intrinsics.fx = intrinsics.fy = p[0];
      intrinsics.cx = p[1];
      intrinsics.cy = p[2];
      return intrinsics;
    case 1:
    case 4:
    case 5:
    case 6:
    case 7:
    case 10:
      if (p.size() < 4) break;
      intrinsics.fx = p[0];
      intrinsics.fy = p[1];
      intrinsics.cx = p[2];
      intrinsics.cy = p[3];
      return intrinsics;
    default:
      break;
  }
  ThrowError("camera ",
             camera.camera_id,
             " has model id ",
             camera.model_id,
             " with ",
             p.size(),
             " parameters, which the look-alike filter cannot read");
}

bool RotationFromEssential(const Eigen::Matrix3d& E,
                           const Eigen::Matrix2Xd& rays1,
                           const Eigen::Matrix2Xd& rays2,
                           Eigen::Matrix3d* rotation) {
  if (!E.allFinite() || E.norm() < 1e-12 || rays1.cols() == 0) return false;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(
      E, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  Eigen::Matrix3d V = svd.matrixV();
  if (U.determinant() < 0) U = -U;
  if (V.determinant() < 0) V = -V;
  Eigen::Matrix3d W;
  W << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  const Eigen::Matrix3d R1 = U * W * V.transpose();
  const Eigen::Matrix3d R2 = U * W.transpose() * V.transpose();
  const Eigen::Vector3d t = U.col(2);
  const Eigen::Matrix3d candidates_R[4] = {R1, R1, R2, R2};
  const Eigen::Vector3d candidates_t[4] = {t, -t, t, -t};
  int best = -1;
  int best_count = 0;
  for (int c = 0; c < 4; ++c) {
    int count = 0;
    for (Eigen::Index i = 0; i < rays1.cols(); ++i) {
      count += InFrontOfBoth(
          candidates_R[c], candidates_t[c], rays1.col(i), rays2.col(i));
    }
    if (count > best_count) {
      best_count = count;
      best = c;
    }
  }
  if (best < 0 || 2 * best_count < rays1.cols()) return false;
  *rotation = candidates_R[best];
  return true;
}

std::vector<Eigen::Matrix3d> RotationsFromHomography(
    const Eigen::Matrix3d& H,
    const Eigen::Matrix2Xd& rays1,
    const Eigen::Matrix2Xd& rays2) {
  std::vector<Eigen::Matrix3d> rotations;
  if (!H.allFinite() || H.norm() < 1e-12 || rays1.cols() == 0) {
    return rotations;
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(
      H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  const Eigen::Vector3d d = svd.singularValues() / svd.singularValues()(1);
  const double s = U.determinant() * V.determinant();
  if (!(d(2) > 1e-9)) return rotations;  // rank < 3
  if (d(0) - d(2) < 1e-9) {
    // A pure rotation: H = R up to scale.
    rotations.push_back(s * U * V.transpose());
    return rotations;
  }
  const double d1 = d(0);
  const double d3 = d(2);
  const double x1 =
      std::sqrt(std::max(0.0, (d1 * d1 - 1) / (d1 * d1 - d3 * d3)));
  const double x3 =
      std::sqrt(std::max(0.0, (1 - d3 * d3) / (d1 * d1 - d3 * d3)));
  const double e1[4] = {x1, x1, -x1, -x1};
  const double e3[4] = {x3, -x3, x3, -x3};
  // d' = +1: rotation about the second axis by theta.
  const double sin_theta =
      std::sqrt(std::max(0.0, (d1 * d1 - 1) * (1 - d3 * d3))) / (d1 + d3);
  const double cos_theta = (1 + d1 * d3) / (d1 + d3);
  const double sin_thetas[4] = {sin_theta, -sin_theta, -sin_theta, sin_theta};
  // d' = -1: a reflection-like rotation by phi.
  const double sin_phi =
      std::sqrt(std::max(0.0, (d1 * d1 - 1) * (1 - d3 * d3))) / (d1 - d3);
  const double cos_phi = (d1 * d3 - 1) / (d1 - d3);
  const double sin_phis[4] = {sin_phi, -sin_phi, -sin_phi, sin_phi};
  std::vector<Eigen::Matrix3d> candidates_R;
  std::vector<Eigen::Vector3d> candidates_t;
  for (int i = 0; i < 4; ++i) {
    Eigen::Matrix3d Rp;
    Rp << cos_theta, 0, -sin_thetas[i], 0, 1, 0, sin_thetas[i], 0, cos_theta;
    candidates_R.push_back(s * U * Rp * V.transpose());
    candidates_t.push_back(U * Eigen::Vector3d(e1[i], 0, -e3[i]) * (d1 - d3));
  }
  for (int i = 0; i < 4; ++i) {
    Eigen::Matrix3d Rp;
    Rp << cos_phi, 0, sin_phis[i], 0, -1, 0, sin_phis[i], 0, -cos_phi;
    candidates_R.push_back(s * U * Rp * V.transpose());
    candidates_t.push_back(U * Eigen::Vector3d(e1[i], 0, e3[i]) * (d1 + d3));
  }
  std::vector<int> counts(candidates_R.size(), 0);
  int best_count = 0;
  for (size_t c = 0; c < candidates_R.size(); ++c) {
    for (Eigen::Index i = 0; i < rays1.cols(); ++i) {
      counts[c] += InFrontOfBoth(
          candidates_R[c], candidates_t[c], rays1.col(i), rays2.col(i));
    }
    best_count = std::max(best_count, counts[c]);
  }
  if (2 * best_count < rays1.cols()) return rotations;
  for (size_t c = 0; c < candidates_R.size(); ++c) {
    if (10 * counts[c] >= 9 * best_count) {
      rotations.push_back(candidates_R[c]);
    }
  }
  return rotations;
}

double RotationAngleDegrees(const Eigen::Matrix3d& rotation) {
  const double c = std::clamp(0.5 * (rotation.trace() - 1.0), -1.0, 1.0);
  return std::acos(c) * 180.0 / M_PI;
}

}  // namespace colmap_gcn

#pragma once

#include <vector>

#include <Eigen/Core>

namespace colmap_gcn {

// x_dst = scale * rotation * x_src + translation.
struct Similarity3d {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d Transform(const Eigen::Vector3d& x) const {
    return scale * rotation * x + translation;
  }
};

// Least-squares similarity mapping src onto dst (Umeyama, PAMI 1991).
// Returns false when it is undetermined: fewer than 3 points, different
// sizes, or points (nearly) collinear or coincident.
bool EstimateSimilarity(const std::vector<Eigen::Vector3d>& src,
                        const std::vector<Eigen::Vector3d>& dst,
                        Similarity3d* similarity);

}  // namespace colmap_gcn

#include "math/similarity_transform.h"

#include <cmath>

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace colmap_gcn {

bool EstimateSimilarity(const std::vector<Eigen::Vector3d>& src,
                        const std::vector<Eigen::Vector3d>& dst,
                        Similarity3d* similarity) {
  if (src.size() != dst.size() || src.size() < 3) return false;
  Eigen::Matrix3Xd src_mat(3, src.size());
  Eigen::Matrix3Xd dst_mat(3, dst.size());
  for (size_t i = 0; i < src.size(); ++i) {
    src_mat.col(i) = src[i];
    dst_mat.col(i) = dst[i];
  }
  // Degenerate when the source spread is (nearly) one-dimensional: the
  // rotation about that line is then undetermined.
  const Eigen::Matrix3Xd centred = src_mat.colwise() - src_mat.rowwise().mean();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(centred * centred.transpose());
  const Eigen::Vector3d singular = svd.singularValues();
  if (singular(0) <= 0 || singular(1) < 1e-12 * singular(0)) return false;
  const Eigen::Matrix4d transform = Eigen::umeyama(src_mat, dst_mat, true);
  const Eigen::Matrix3d sR = transform.topLeftCorner<3, 3>();
  similarity->scale = std::cbrt(sR.determinant());
  if (!(similarity->scale > 0) || !std::isfinite(similarity->scale)) {
    return false;
  }
  similarity->rotation = sR / similarity->scale;
  similarity->translation = transform.topRightCorner<3, 1>();
  return true;
}

}  // namespace colmap_gcn

#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "scene/database.h"

namespace colmap_gcn {
namespace test {

typedef Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
    FeatureKeypoints;  // rows x {2,4,6} columns, x y [a11 a12 a21 a22]
typedef Eigen::Matrix<uint32_t, Eigen::Dynamic, 2, Eigen::RowMajor>
    FeatureMatches;  // point2D_idx in image_id1, in image_id2

struct TwoViewGeometry {
  int config = 0;
  FeatureMatches inlier_matches;  // oriented as requested (image_id1 first)
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector4d qvec = Eigen::Vector4d(1, 0, 0, 0);  // w x y z
  Eigen::Vector3d tvec = Eigen::Vector3d::Zero();
};

// Reads of a COLMAP database that only tests need (cameras, keypoints,
// matches, full two-view geometries), on top of the library's Database so
// that they share its opening checks. Same conventions: a missing row gives
// an empty result, a blob whose size does not match its shape throws Error.
class DatabaseInspector : public Database {
 public:
  using Database::Database;

  size_t NumCameras() const;
  size_t NumKeypoints() const;          // summed over images
  size_t NumMatchedPairs() const;       // rows in matches
  size_t NumTwoViewGeometries() const;  // rows in two_view_geometries

  bool ExistsImageWithName(const std::string& name) const;
  DatabaseImage ReadImageWithName(const std::string& name) const;  // throws

  FeatureKeypoints ReadKeypoints(image_t image_id) const;
  size_t NumKeypointsForImage(image_t image_id) const;

  // Matches oriented so that column 0 indexes image_id1.
  FeatureMatches ReadMatches(image_t image_id1, image_t image_id2) const;
  std::vector<image_pair_t> ReadMatchedPairIds() const;  // ordered
  bool ExistsMatches(image_t image_id1, image_t image_id2) const;

  // Oriented like ReadMatches; for image_id1 > image_id2 the stored geometry
  // is inverted as COLMAP does (F and E transposed, H inverted, inverse
  // relative pose). F/E/H are stored row-major.
  TwoViewGeometry ReadTwoViewGeometry(image_t image_id1,
                                      image_t image_id2) const;
  bool ExistsTwoViewGeometry(image_t image_id1, image_t image_id2) const;
};

}  // namespace test
}  // namespace colmap_gcn

#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "scene/database.h"

namespace colmap_gcn {

// Feature matches of a pair: column 0 indexes image_id1's keypoints (the
// smaller id), column 1 image_id2's, as COLMAP stores them.
typedef Eigen::Matrix<uint32_t, Eigen::Dynamic, 2, Eigen::RowMajor>
    FeatureMatches;

// A verified pair as the look-alike filter reads it: the inlier matches
// (column 0 indexes image_id1, the smaller id) and the estimated matrices.
struct VerifiedTwoViewGeometry {
  image_pair_t pair_id = kInvalidImagePairId;
  image_t image_id1 = kInvalidImageId;
  image_t image_id2 = kInvalidImageId;
  int config = 0;
  FeatureMatches inliers;
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero();  // x2' F x1 = 0
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();  // x2 ~ H x1
};

// A pair whose two_view_geometries row was moved aside, with why.
struct HiddenTwoViewGeometry {
  image_pair_t pair_id = kInvalidImagePairId;
  std::string reason;
  double score = 0;
  size_t num_inliers = 0;  // of the original row
};

// The side table that keeps the rows of hidden pairs.
constexpr char kHiddenPairsTable[] = "gcn_lookalike_pairs";

// The reads and writes of the look-alike filter: verified pairs with their
// inliers, keypoint positions and cameras, and hiding a pair from COLMAP's
// mapper without losing it. A hidden pair's original two_view_geometries row
// (every column, whatever the schema) goes to kHiddenPairsTable with its
// reason and score; in two_view_geometries it becomes an unverified row
// (config 0, no inliers), as COLMAP writes for a pair that failed
// verification, so that the mapper ignores it and matching does not verify
// it again. RestoreHiddenPairs puts every original row back.
class TwoViewGeometryStore : public Database {
 public:
  explicit TwoViewGeometryStore(const std::string& path,
                                Mode mode = Mode::kReadOnly);

  // Keypoint positions (x, y; pixel centre at 0.5), one row per keypoint.
  Eigen::Matrix<float, Eigen::Dynamic, 2> ReadKeypointPositions(
      image_t image_id) const;

  // The pair's row of the matches table (no row: no matches).
  FeatureMatches ReadMatches(image_pair_t pair_id) const;

  // Every pair that IsVerifiedTwoViewGeometry accepts, ordered by pair_id.
  std::vector<VerifiedTwoViewGeometry> ReadVerifiedTwoViewGeometries(
      size_t min_num_inliers) const;

  // Pairs already hidden (none when the side table does not exist).
  std::vector<HiddenTwoViewGeometry> ReadHiddenPairs() const;

  // Moves the rows of these pairs aside in one transaction; a pair already
  // hidden or without a row is skipped. Requires kReadWrite.
  void HidePairs(const std::vector<HiddenTwoViewGeometry>& pairs);

  // Puts every hidden row back and drops the side table, in one
  // transaction; returns how many rows came back. Requires kReadWrite.
  size_t RestoreHiddenPairs();

 private:
  bool HasHiddenPairsTable() const;
  std::vector<std::string> TwoViewGeometryColumns() const;

  bool writable_ = false;
};

}  // namespace colmap_gcn

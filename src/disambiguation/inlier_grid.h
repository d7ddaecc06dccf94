#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "scene/two_view_geometry_store.h"

namespace colmap_gcn {

// Where a verified pair's inliers lie in its two images, on a coarse grid:
// the evidence that orders the view graph's edges for the look-alike filter
// (lookalike_decision.h, docs/lookalike.md).

typedef Eigen::Matrix<float, Eigen::Dynamic, 2> KeypointPositions;

// kInlierGrid x kInlierGrid cells over each image.
constexpr int kInlierGrid = 8;

// A cell "reaches" an image's partner when the pair has at least this many
// inliers in it (fewer are as likely stray matches as overlap).
constexpr int kCellReachInliers = 3;

// Fewer distinctive inliers than this are counted as none: cells just over
// the reach threshold give a few by chance wherever every partner overlaps.
constexpr int kMinDistinctiveInliers = 10;

// An image with fewer verified pairs has no "few of its pairs": its pairs'
// distinctive inliers count as none.
constexpr int kMinDistinctivePartners = 6;

// The grid cell of each inlier in each image, in the pair's inlier order;
// kNoCell for an inlier whose keypoint index is out of range.
struct PairInlierCells {
  static constexpr uint8_t kNoCell = 255;
  std::vector<uint8_t> cells1;
  std::vector<uint8_t> cells2;
};

PairInlierCells ComputeInlierCells(const VerifiedTwoViewGeometry& pair,
                                   const KeypointPositions& keypoints1,
                                   const KeypointPositions& keypoints2,
                                   const Eigen::Vector2d& size1,
                                   const Eigen::Vector2d& size2);

// Cells holding an inlier, the fewer of the two images.
int CoveredCells(const PairInlierCells& cells);

// Per image, how many of its verified pairs reach each cell. Duplicate
// structure (one print on the front and back of an object, identical
// objects) is matched by an image's real partners and its look-alike
// partners alike, so it fills the cells most partners reach; what tells a
// real partner is overlap where few partners reach, such as the room behind
// the object.
class InlierCellReach {
 public:
  explicit InlierCellReach(int num_images);

  // Counts one verified pair between the two images.
  void AddPair(int image1, int image2, const PairInlierCells& cells);

  // The pair's inliers that lie, in both images, in cells reached by at most
  // max(1, share * partners) of that image's verified pairs; 0 when fewer
  // than kMinDistinctiveInliers, or when either image has fewer than
  // kMinDistinctivePartners pairs.
  int DistinctiveInliers(int image1,
                         int image2,
                         const PairInlierCells& cells,
                         double share) const;

 private:
  std::vector<std::vector<int>> reach_;  // image -> cell -> pairs
  std::vector<int> num_partners_;
};

}  // namespace colmap_gcn

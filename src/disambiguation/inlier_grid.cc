#include "disambiguation/inlier_grid.h"

#include <algorithm>
#include <cmath>

namespace colmap_gcn {
namespace {

constexpr int kNumCells = kInlierGrid * kInlierGrid;

uint8_t CellOf(const KeypointPositions& keypoints,
               const uint32_t k,
               const Eigen::Vector2d& size) {
  if (k >= keypoints.rows()) return PairInlierCells::kNoCell;
  const int x =
      std::clamp(static_cast<int>(kInlierGrid * keypoints(k, 0) / size.x()),
                 0,
                 kInlierGrid - 1);
  const int y =
      std::clamp(static_cast<int>(kInlierGrid * keypoints(k, 1) / size.y()),
                 0,
                 kInlierGrid - 1);
  return static_cast<uint8_t>(y * kInlierGrid + x);
}

// Inliers per cell of one image's side of a pair.
std::vector<int> CellCounts(const std::vector<uint8_t>& cells) {
  std::vector<int> counts(kNumCells, 0);
  for (const uint8_t cell : cells) {
    if (cell != PairInlierCells::kNoCell) ++counts[cell];
  }
  return counts;
}

}  // namespace

PairInlierCells ComputeInlierCells(const VerifiedTwoViewGeometry& pair,
                                   const KeypointPositions& keypoints1,
                                   const KeypointPositions& keypoints2,
                                   const Eigen::Vector2d& size1,
                                   const Eigen::Vector2d& size2) {
  PairInlierCells cells;
  cells.cells1.reserve(pair.inliers.rows());
  cells.cells2.reserve(pair.inliers.rows());
  for (Eigen::Index i = 0; i < pair.inliers.rows(); ++i) {
    const uint8_t cell1 = CellOf(keypoints1, pair.inliers(i, 0), size1);
    const uint8_t cell2 = CellOf(keypoints2, pair.inliers(i, 1), size2);
    const bool valid =
        cell1 != PairInlierCells::kNoCell && cell2 != PairInlierCells::kNoCell;
    cells.cells1.push_back(valid ? cell1 : PairInlierCells::kNoCell);
    cells.cells2.push_back(valid ? cell2 : PairInlierCells::kNoCell);
  }
  return cells;
}

int CoveredCells(const PairInlierCells& cells) {
  const std::vector<int> counts1 = CellCounts(cells.cells1);
  const std::vector<int> counts2 = CellCounts(cells.cells2);
  const auto covered = [](const std::vector<int>& counts) {
    return static_cast<int>(std::count_if(
        counts.begin(), counts.end(), [](int c) { return c > 0; }));
  };
  return std::min(covered(counts1), covered(counts2));
}

InlierCellReach::InlierCellReach(const int num_images)
    : reach_(num_images, std::vector<int>(kNumCells, 0)),
      num_partners_(num_images, 0) {}

void InlierCellReach::AddPair(const int image1,
                              const int image2,
                              const PairInlierCells& cells) {
  for (const auto& [image, side] : {std::make_pair(image1, &cells.cells1),
                                    std::make_pair(image2, &cells.cells2)}) {
    const std::vector<int> counts = CellCounts(*side);
    for (int c = 0; c < kNumCells; ++c) {
      reach_[image][c] += counts[c] >= kCellReachInliers;
    }
    ++num_partners_[image];
  }
}

int InlierCellReach::DistinctiveInliers(const int image1,
                                        const int image2,
                                        const PairInlierCells& cells,
                                        const double share) const {
  if (std::min(num_partners_[image1], num_partners_[image2]) <
      kMinDistinctivePartners) {
    return 0;
  }
  const int max_reach1 =
      std::max(1, static_cast<int>(std::floor(share * num_partners_[image1])));
  const int max_reach2 =
      std::max(1, static_cast<int>(std::floor(share * num_partners_[image2])));
  int count = 0;
  for (size_t i = 0; i < cells.cells1.size(); ++i) {
    const uint8_t cell1 = cells.cells1[i];
    const uint8_t cell2 = cells.cells2[i];
    if (cell1 == PairInlierCells::kNoCell) continue;
    count += reach_[image1][cell1] <= max_reach1 &&
             reach_[image2][cell2] <= max_reach2;
  }
  return count >= kMinDistinctiveInliers ? count : 0;
}

}  // namespace colmap_gcn

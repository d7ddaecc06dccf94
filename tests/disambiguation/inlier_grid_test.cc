#include "disambiguation/inlier_grid.h"

#include <gtest/gtest.h>

namespace colmap_gcn {
namespace {

// A pair whose inliers sit at the given pixels of two 640 x 480 images (the
// same pixel in both).
struct GridPair {
  VerifiedTwoViewGeometry pair;
  KeypointPositions keypoints;
};

GridPair PairAt(const std::vector<Eigen::Vector2f>& pixels) {
  GridPair grid;
  grid.keypoints.resize(static_cast<Eigen::Index>(pixels.size()), 2);
  grid.pair.inliers.resize(static_cast<Eigen::Index>(pixels.size()), 2);
  for (size_t i = 0; i < pixels.size(); ++i) {
    grid.keypoints.row(i) = pixels[i].transpose();
    grid.pair.inliers(i, 0) = static_cast<uint32_t>(i);
    grid.pair.inliers(i, 1) = static_cast<uint32_t>(i);
  }
  return grid;
}

// n inliers spread over the cells of columns [x0, x1) and rows [y0, y1) of
// the 8 x 8 grid (80 x 60 pixels a cell).
std::vector<Eigen::Vector2f> Block(int x0, int x1, int y0, int y1, int n) {
  std::vector<Eigen::Vector2f> pixels;
  for (int k = 0; k < n; ++k) {
    const int cx = x0 + k % (x1 - x0);
    const int cy = y0 + (k / (x1 - x0)) % (y1 - y0);
    pixels.emplace_back(80.0f * cx + 5.0f + (k % 7) * 10.0f,
                        60.0f * cy + 5.0f + (k % 5) * 10.0f);
  }
  return pixels;
}

PairInlierCells Cells(const GridPair& grid) {
  const Eigen::Vector2d size(640, 480);
  return ComputeInlierCells(
      grid.pair, grid.keypoints, grid.keypoints, size, size);
}

TEST(InlierGrid, CoveredCellsCountsTheFewerImage) {
  const GridPair grid = PairAt(Block(2, 6, 2, 6, 64));  // 4 x 4 cells
  EXPECT_EQ(CoveredCells(Cells(grid)), 16);
  // An inlier whose keypoint index is out of range lands in no cell.
  GridPair broken = grid;
  broken.pair.inliers(0, 1) = 1000;
  const PairInlierCells cells = Cells(broken);
  EXPECT_EQ(cells.cells1[0], PairInlierCells::kNoCell);
  EXPECT_EQ(cells.cells2[0], PairInlierCells::kNoCell);
}

// Image 0 of a printed object: six partners match the print in the middle
// of the view (four real neighbours and two look-alikes from the other
// side, which match nothing else); only its nearest neighbour also matches
// the room at the left edge. The look-alikes have the most inliers and
// cover as many cells, but none of their inliers is distinctive.
TEST(InlierGrid, DistinctiveInliersAreWhereFewPartnersReach) {
  const std::vector<Eigen::Vector2f> print = Block(2, 6, 1, 7, 240);
  std::vector<Eigen::Vector2f> nearest = Block(2, 6, 1, 7, 150);
  for (const Eigen::Vector2f& p : Block(0, 2, 1, 7, 40)) nearest.push_back(p);
  const std::vector<Eigen::Vector2f> neighbour = Block(2, 6, 1, 7, 120);
  const PairInlierCells nearest_cells = Cells(PairAt(nearest));
  const PairInlierCells neighbour_cells = Cells(PairAt(neighbour));
  const PairInlierCells lookalike_cells = Cells(PairAt(print));
  EXPECT_GE(CoveredCells(lookalike_cells), CoveredCells(neighbour_cells));

  // Images 1-6 have pairs of their own too, elsewhere in the view (the
  // bottom-right cell), so that each has enough pairs to tell few from
  // many.
  const PairInlierCells elsewhere = Cells(PairAt(Block(7, 8, 7, 8, 5)));
  const auto add_other_pairs = [&](InlierCellReach* reach) {
    for (int image = 1; image <= 6; ++image) {
      for (int other = 7; other < 12; ++other) {
        reach->AddPair(image, other, elsewhere);
      }
    }
  };
  InlierCellReach reach(12);
  reach.AddPair(0, 1, nearest_cells);
  // With fewer than kMinDistinctivePartners pairs an image has no "few".
  EXPECT_EQ(reach.DistinctiveInliers(0, 1, nearest_cells, 0.35), 0);
  for (int image : {2, 3, 4}) reach.AddPair(0, image, neighbour_cells);
  for (int image : {5, 6}) reach.AddPair(0, image, lookalike_cells);
  add_other_pairs(&reach);
  // On the partners' side each cell of this pair is reached once, so they
  // do not limit: the room's 40 inliers are distinctive at
  // share 0.35 (cells reached by at most 2 of 6 pairs), the print's are
  // not.
  EXPECT_EQ(reach.DistinctiveInliers(0, 1, nearest_cells, 0.35), 40);
  EXPECT_EQ(reach.DistinctiveInliers(0, 2, neighbour_cells, 0.35), 0);
  EXPECT_EQ(reach.DistinctiveInliers(0, 5, lookalike_cells, 0.35), 0);
  // Share 1: every inlier counts.
  EXPECT_EQ(reach.DistinctiveInliers(0, 5, lookalike_cells, 1.0), 240);
  // A few distinctive inliers are noise: counted as none.
  InlierCellReach sparse(12);
  std::vector<Eigen::Vector2f> few = Block(2, 6, 1, 7, 150);
  for (const Eigen::Vector2f& p :
       Block(0, 1, 1, 4, kMinDistinctiveInliers - 1)) {
    few.push_back(p);
  }
  const PairInlierCells few_cells = Cells(PairAt(few));
  sparse.AddPair(0, 1, few_cells);
  for (int image : {2, 3, 4, 5, 6}) sparse.AddPair(0, image, lookalike_cells);
  add_other_pairs(&sparse);
  EXPECT_EQ(sparse.DistinctiveInliers(0, 1, few_cells, 0.35), 0);
}

}  // namespace
}  // namespace colmap_gcn

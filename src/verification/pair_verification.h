#pragma once

#include <string>
#include <vector>

#include "scene/two_view_geometry_store.h"
#include "util/types.h"
#include "verification/exact_matching.h"
#include "verification/fundamental_ransac.h"

namespace colmap_gcn {

// Two-view verification that repeats exactly: EstimateFundamentalRansac on
// a pair's stored matches, seeded by the pair's id. COLMAP 3.8's own
// verification does not repeat (its RANSAC threads seed themselves from the
// clock), so anything that decides on verification -- the adaptive loop's
// rounds -- decides on this, while COLMAP's rows still go to the mapper.
struct ExactVerificationOptions {
  FundamentalRansacOptions ransac;
  // COLMAP's --SiftMatching.min_num_inliers.
  int min_num_inliers = kDefaultMinNumInliers;
  // Pairs verified in parallel (<= 0: every hardware thread); the results do
  // not depend on it.
  int num_threads = -1;

  void Check() const;
};

// One pair's result in the look-alike filter's terms: config kUncalibrated
// with F and the inlier matches when at least min_num_inliers (and eight)
// matches fit one F, else config kUndefined with no inliers. `matches` and
// the ids as COLMAP stores them: image_id1 < image_id2.
VerifiedTwoViewGeometry VerifyPairExactly(
    const FeatureMatches& matches,
    const Eigen::Matrix<float, Eigen::Dynamic, 2>& keypoints1,
    const Eigen::Matrix<float, Eigen::Dynamic, 2>& keypoints2,
    image_t image_id1,
    image_t image_id2,
    const ExactVerificationOptions& options);

// Every pair of `pairs` (either order), in the same order, from a COLMAP
// database's matches and keypoints; a pair without a matches row verifies
// as kUndefined. Throws Error naming a match whose keypoint index is out of
// range.
std::vector<VerifiedTwoViewGeometry> VerifyPairsExactly(
    const TwoViewGeometryStore& database,
    const std::vector<ImagePair>& pairs,
    const ExactVerificationOptions& options);

}  // namespace colmap_gcn

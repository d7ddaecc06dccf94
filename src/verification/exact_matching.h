#pragma once

#include <Eigen/Core>

#include <vector>

#include "scene/two_view_geometry_store.h"
#include "util/types.h"

namespace colmap_gcn {

// Feature matching with the rules of COLMAP's SIFT matcher (nearest
// neighbour by descriptor angle, Lowe's ratio test, a maximum distance and a
// cross check) but exhaustive instead of approximate: COLMAP 3.8 searches
// with randomised kd-trees, so its matches of the same two images differ
// from run to run. Here every dot product of two uint8 descriptors is an
// integer below 2^24 and therefore exact in float whatever the summation
// order, and ties go to the lower index: the same descriptors give the same
// matches on every machine and thread count.
struct ExactMatchingOptions {
  // COLMAP's --SiftMatching.max_ratio: best / second-best angle.
  double max_ratio = 0.8;
  // COLMAP's --SiftMatching.max_distance: the largest angle, in radians.
  double max_distance = 0.7;
  // COLMAP's --SiftMatching.cross_check.
  bool cross_check = true;

  void Check() const;
};

// Matches (column 0 indexes descriptors1, column 1 descriptors2), ordered by
// column 0. Descriptors are COLMAP's: 128 uint8 values of norm ~512.
FeatureMatches MatchDescriptorsExactly(const FeatureDescriptors& descriptors1,
                                       const FeatureDescriptors& descriptors2,
                                       const ExactMatchingOptions& options);

// The matches of each pair (smaller image id first in each), from a COLMAP
// database's descriptors, num_threads pairs at a time (<= 0: every hardware
// thread; the result does not depend on it). Reads the descriptors of the
// images the pairs name once.
std::vector<FeatureMatches> MatchPairsExactly(
    const TwoViewGeometryStore& database,
    const std::vector<ImagePair>& pairs,
    const ExactMatchingOptions& options,
    int num_threads);

}  // namespace colmap_gcn

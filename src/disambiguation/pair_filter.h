#pragma once

#include <string>
#include <vector>

#include "disambiguation/focal_calibration.h"
#include "disambiguation/lookalike_decision.h"
#include "disambiguation/pair_evidence.h"
#include "scene/database.h"
#include "scene/two_view_geometry_store.h"

namespace colmap_gcn {

// The look-alike (duplicate structure) filter on a matched database: which
// verified pairs to hide from COLMAP's mapper (docs/lookalike.md).
struct PairFilterOptions {
  LookalikeDecisionOptions decision;

  // Pairs with fewer inliers are not verified (COLMAP's
  // --SiftMatching.min_num_inliers).
  int min_num_inliers = kDefaultMinNumInliers;

  // An edge's strength counts the inliers in grid cells that at most this
  // share of each image's verified pairs reach (inlier_grid.h): duplicate
  // structure fills the cells most partners reach.
  double distinctive_share = 0.35;

  // Inlier rays used for the cheirality test of each pair (evenly spaced
  // over the pair's inliers).
  int max_rays_per_pair = 200;

  // Cameras whose focal length is COLMAP's guess (prior_focal_length 0)
  // get a focal length self-calibrated from the verified pairs' F before
  // the rotations are recovered; off: the database's values are used.
  bool self_calibrate_focal = true;  // default true
  FocalCalibrationOptions focal_calibration;

  // Trusted focal lengths (prior_focal_length 1: EXIF or the user) are
  // checked against the loops of the verified graph: when the loop test
  // fails many strong pairs, one factor for all of them (0.5-2) that cuts
  // the failures by at least a quarter replaces them (a cropped photo's
  // EXIF focal length is off by the crop factor; pair_filter.cc).
  bool check_trusted_focal = true;  // default true

  // -1: all cores; the decisions do not depend on it.
  int num_threads = -1;

  // Where to write one CSV line per verified pair (image names, inliers,
  // rotation error, hops, decision); empty: none.
  std::string pairs_csv_path = "";

  void Check() const;
};

// One verified pair with its decision.
struct PairFilterEntry {
  image_pair_t pair_id = kInvalidImagePairId;
  std::string name1;
  std::string name2;
  int num_inliers = 0;
  int covered_cells = 0;  // CoveredCells (inlier_grid.h)
  int strength = 0;       // ViewGraphEdge::strength
  int config = 0;         // COLMAP's two-view configuration
  PairRotations rotations;
  LookalikeDecision decision;
};

struct PairFilterReport {
  std::string database_path;
  size_t num_images = 0;
  size_t num_verified_pairs = 0;         // before this run
  size_t num_without_rotation = 0;       // no relative rotation recovered
  size_t num_already_hidden = 0;         // by an earlier run
  std::vector<PairFilterEntry> entries;  // every verified pair
  size_t num_rejected = 0;               // hidden by this run
  // Focal self-calibration: guessed cameras, the median scale applied to
  // their focal lengths and the median essential inconsistency before/after.
  size_t num_guessed_cameras = 0;
  // Guessed cameras the self-calibration declined: no rotation is judged
  // for their pairs.
  size_t num_uncalibrated_cameras = 0;
  double median_focal_scale = 1;
  // The focal length check: the factor applied to the trusted focal
  // lengths (1: kept) and the strong pairs failing the loop test with the
  // focal lengths before and after it.
  double trusted_focal_scale = 1;
  size_t focal_check_failures_before = 0;
  size_t focal_check_failures_after = 0;
  double focal_cost_before = 0;
  double focal_cost_after = 0;
  double seconds = 0;
};

// Decides every verified pair of a database without changing it.
PairFilterReport FindLookalikePairs(const TwoViewGeometryStore& database,
                                    const PairFilterOptions& options);

// The same decision on given verified pairs (each pair once, image_id1 <
// image_id2) instead of the database's two_view_geometries, with the
// database's images, cameras and keypoints: for a caller that verified
// pairs itself (the adaptive loop, verification/pair_verification.h).
PairFilterReport FindLookalikePairs(
    const TwoViewGeometryStore& database,
    const std::vector<VerifiedTwoViewGeometry>& verified_pairs,
    const PairFilterOptions& options);

// The rejected pairs' ids (sorted), for a caller that must not trust them
// (the adaptive pairing loop).
std::vector<image_pair_t> RejectedPairIds(const PairFilterReport& report);

// FindLookalikePairs, then hides the rejected pairs in the database through
// a working copy that replaces it only once verified (docs/reliability.md).
PairFilterReport FilterLookalikePairs(const std::string& database_path,
                                      const PairFilterOptions& options);

// Puts every pair hidden by the filter back; returns how many. Through a
// working copy as well.
size_t RestoreLookalikePairs(const std::string& database_path);

// What was removed and why.
void PrintPairFilterReport(const PairFilterReport& report, bool list_pairs);

}  // namespace colmap_gcn

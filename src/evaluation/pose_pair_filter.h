#pragma once

#include <string>
#include <vector>

#include "controllers/colmap_runner.h"
#include "controllers/pair_matching.h"
#include "pairing/pairs_io.h"
#include "scene/reconstruction.h"

namespace colmap_gcn {

// Which pairs the ground-truth labelling matches. Exhaustive matching of a
// 100-150-image scene costs hours on two cores; most pairs of a ring or
// turntable capture see the object from opposite sides and can share no
// SIFT match. The rule needs only the poses and intrinsics of gt/ (no
// depth: the gt/ models carry no points):
//
//   For a 3D point X seen by cameras i and j, the viewing rays X - C_i and
//   X - C_j lie within h_i and h_j of the optical axes a_i and a_j (h: the
//   largest angle between the axis and a ray through the image, at a
//   corner). By the triangle inequality on the sphere, the viewpoint change
//   at X, angle(C_i - X, C_j - X), is at least
//       angle(a_i, a_j) - h_i - h_j.
//   A pair whose bound exceeds max_viewpoint_change_deg cannot share a
//   point that SIFT matches, and is not matched.
//
// Cameras far apart that face the same way (video trajectories) are kept:
// without a scene depth nothing bounds their overlap.
struct PosePairFilterOptions {
  // Largest viewpoint change at a 3D point across which two images can
  // still share a SIFT match, in degrees. SIFT matches fail beyond about
  // 60-70 degrees of out-of-plane rotation (Morel & Yu 2009, ASIFT; the
  // corpus uses 70). 0: no filter, every pair is matched (exhaustive).
  double max_viewpoint_change_deg = 0;

  bool Enabled() const { return max_viewpoint_change_deg > 0; }
  void Check() const;
};

// The largest angle (radians) between the optical axis and a ray through
// the image, reached at one of its corners; lens distortion is ignored.
// Fisheye and FOV models, or an unknown model, return pi (no bound).
double MaxRayAngleFromAxis(const ModelCamera& camera);

// Lower bound (degrees) on the viewpoint change at any 3D point both images
// see (see above); never negative.
double MinViewpointChangeDeg(const ModelImage& image1,
                             const ModelCamera& camera1,
                             const ModelImage& image2,
                             const ModelCamera& camera2);

struct PosePairSelection {
  size_t num_images = 0;  // images with a pose in the model
  // All unordered pairs of those images, split into the ones to match
  // (sorted, name1 < name2) and the number skipped.
  std::vector<ImageNamePair> kept;
  size_t num_skipped = 0;
};

// Applies the rule to every pair of images in the model. Throws Error if
// an image's camera is missing from the model.
PosePairSelection SelectPosePairs(const Reconstruction& model,
                                  const PosePairFilterOptions& options);

struct LabelMatchingSummary {
  std::string database_path;     // the matched database
  size_t num_images = 0;         // images of the database
  size_t num_gt_images = 0;      // of those, with a ground-truth pose
  size_t num_pairs_total = 0;    // all pairs of the database's images
  size_t num_pairs_matched = 0;  // pairs handed to COLMAP
  size_t num_pairs_verified = 0;
  double matching_seconds = 0;  // this run's matching (0 when cached)
};

// Matches, for the labels, the pairs of ground-truth images that pass the
// filter: in work_dir/database.db, a copy of base_db made once, so an
// interrupted run resumes in it (pairs already matched are not sent to
// COLMAP again). Pairs with an image without a pose are unlabelled and not
// matched. Records what it did in work_dir/label_matching.json; returns it.
// ground_truth holds the poses of the database's images (names as in the
// database).
LabelMatchingSummary MatchPosePairsForLabels(
    const ColmapRunner& colmap,
    const std::string& base_db,
    const Reconstruction& ground_truth,
    const PosePairFilterOptions& options,
    const PairMatchingOptions& matching,
    const std::string& work_dir);

}  // namespace colmap_gcn

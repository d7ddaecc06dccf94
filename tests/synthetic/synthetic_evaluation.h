#pragma once

// Evaluating a COLMAP run on a synthetic scene against its ground truth, for
// the synthetic COLMAP tests and the synthetic_eval tool.

#include <string>
#include <vector>

#include "scene/database.h"
#include "scene/reconstruction.h"
#include "synthetic/pair_overlap.h"

namespace colmap_gcn {

// How well a reconstruction's cameras agree with the ground truth.
struct PoseAlignmentResult {
  int num_gt_images = 0;
  // Model images whose name is in the ground truth.
  int num_registered = 0;
  // Largest distance between two ground-truth camera centres.
  double scene_size = 0.0;
  // Camera centre errors after the similarity alignment, in ground-truth
  // units.
  double median_position_error = 0.0;
  double max_position_error = 0.0;
  double scale = 0.0;  // of the model-to-ground-truth similarity

  double RegisteredFraction() const {
    return num_gt_images > 0 ? double(num_registered) / num_gt_images : 0.0;
  }
  double RelativeMedianError() const {
    return scene_size > 0 ? median_position_error / scene_size : 0.0;
  }
};

// Matches model images to ground-truth images by name and aligns the model's
// camera centres to the ground truth with a similarity transform (Umeyama,
// least squares). Throws Error if fewer than 3 images match or their
// centres are collinear.
PoseAlignmentResult AlignToGroundTruth(const Reconstruction& ground_truth,
                                       const Reconstruction& model);

// The model with the most images among <sparse_path>/0, /1, ... (mapper
// output). Throws Error if there is none.
Reconstruction ReadLargestModel(const std::string& sparse_path);

// One row of a COLMAP 3.8 database's two_view_geometries table.
struct TwoViewGeometryRow {
  std::string name1;
  std::string name2;
  int config = 0;
  int num_inliers = 0;

  // IsVerifiedTwoViewGeometry (scene/database.h).
  bool IsVerified(int min_num_inliers = kDefaultMinNumInliers) const;
};

// Reads two_view_geometries with image names (opened read-only). Throws
// Error naming the database on failure.
std::vector<TwoViewGeometryRow> ReadTwoViewGeometries(
    const std::string& database_path);

// Ground-truth overlap against geometric verification over the pairs of the
// table (a pair absent from two_view_geometries counts as not verified).
struct OverlapAgreement {
  // Scene pairs with min(overlap12, overlap21) >= threshold.
  int num_overlap_pairs = 0;
  int num_overlap_verified = 0;
  // Scene pairs sharing no surface sample.
  int num_zero_pairs = 0;
  int num_zero_verified = 0;
  // Scene pairs with 0 < min(overlap12, overlap21) < low_threshold.
  int num_low_pairs = 0;
  int num_low_verified = 0;
  // Pairs with a distractor image (not counted in the zero pairs above).
  int num_distractor_pairs = 0;
  int num_distractor_verified = 0;
  // All verified pairs of the table.
  int num_verified = 0;

  double OverlapVerifiedFraction() const {
    return num_overlap_pairs > 0
               ? double(num_overlap_verified) / num_overlap_pairs
               : 0.0;
  }
};

OverlapAgreement CompareOverlapWithVerification(
    const PairOverlapTable& table,
    const std::vector<TwoViewGeometryRow>& geometries,
    const std::vector<std::string>& distractor_names,
    double threshold = 0.3,
    int min_num_inliers = kDefaultMinNumInliers,
    double low_threshold = 0.05);

}  // namespace colmap_gcn

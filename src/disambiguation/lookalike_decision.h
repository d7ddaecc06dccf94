#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "util/types.h"

namespace colmap_gcn {

// A verified pair as the decision sees it: the images as indices 0..n-1, its
// inlier count and, where one could be recovered, the measured relative
// rotation R = R2 * R1^T (camera 2's orientation relative to camera 1's).
// A pair's geometry may allow more than one rotation (a homography's
// decompositions, E against H): `rotation` is the one the tree may chain
// (has_rotation: well determined), `alternatives` the others; the loop test
// rejects a pair only when none of them agrees with the chained rotation.
struct ViewGraphEdge {
  image_pair_t pair_id = kInvalidImagePairId;  // orders ties
  int image1 = -1;
  int image2 = -1;
  int num_inliers = 0;
  // How strongly the pair overlaps: orders the edges (more first; ties by
  // coverage, then num_inliers, then pair_id). The filter counts the inliers
  // that lie where few of either image's partners match (pair_filter.h,
  // distinctive_share), so that a partner matching only the duplicated
  // structure every partner matches weighs less than one that also shares
  // the rest of the view.
  int strength = 0;
  // The grid cells its inliers cover, the fewer of the two images: many
  // matches on one small repeated object weigh less than matches spread
  // over the whole view.
  int coverage = 0;
  bool has_rotation = false;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  std::vector<Eigen::Matrix3d> alternatives;
  // The mean direction of its inliers' rays in each camera (unit vectors,
  // camera coordinates), where both cameras' focal lengths are trusted or
  // self-calibrated: the parallax test needs no rotation of the pair's own.
  bool has_view_rays = false;
  Eigen::Vector3d view_ray1 = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d view_ray2 = Eigen::Vector3d::UnitZ();
};

// How the look-alike filter decides (docs/lookalike.md). One parameter set
// for every scene.
struct LookalikeDecisionOptions {
  // An edge belongs to the backbone when it is among the
  // backbone_neighbors strongest of both its images.
  int backbone_neighbors = 4;

  // A pair whose measured rotation disagrees by more than this with the
  // rotation chained along the backbone's maximum spanning tree is a
  // look-alike (degrees).
  double max_rotation_error = 30.0;

  // A pair with fewer inliers is never judged by its own rotation: it is too
  // often ill-determined (inliers on a small patch; docs/lookalike.md).
  int min_evidence_inliers = 60;

  // A pair with fewer than min_evidence_inliers outside the tree whose mean
  // inlier rays, turned by the chained rotation, would see their common
  // surface from directions more than this apart, and whose own rotation
  // (if any) fails the loop test too, is a look-alike (degrees): a weak
  // pair is judged by where its inliers lie as well as by its rotation,
  // each unreliable alone (docs/lookalike.md). 180 turns it off.
  double max_view_parallax = 100.0;

  // A pair whose images are more than this many backbone hops apart
  // (without the pair itself) is a look-alike; 0 turns this test off.
  int max_backbone_hops = 0;

  void Check() const;
};

enum class LookalikeReason {
  kKept = 0,
  kRotationLoop = 1,  // its rotation contradicts the chained rotations
  kContext = 2,       // its images are far apart in the backbone
  kViewParallax = 3,  // the chained rotation says its images face away
};

const char* LookalikeReasonName(LookalikeReason reason);

struct LookalikeDecision {
  LookalikeReason reason = LookalikeReason::kKept;
  bool in_backbone = false;
  bool in_tree = false;
  // Degrees between the chained rotation and the closest of the pair's
  // measured ones; -1 when either is missing (no rotation, or the images in
  // different trees).
  double rotation_error = -1;
  // Degrees between the pair's mean inlier rays under the chained rotation
  // (the angle at which the two cameras would see the matched surface); -1
  // without view rays or across trees.
  double view_parallax = -1;
  // Degrees the tree path between its images turns, unwrapped (steps back
  // and forth cancel); -1 across trees.
  double path_rotation = -1;
  // Backbone hops between the images without this edge; -1 if unconnected.
  int backbone_hops = -1;

  bool Rejected() const { return reason != LookalikeReason::kKept; }
};

// One decision per edge, in the order given. Deterministic: depends only on
// the edges (ties broken by pair_id), never on their order or on threads.
std::vector<LookalikeDecision> DecideLookalikePairs(
    int num_images,
    const std::vector<ViewGraphEdge>& edges,
    const LookalikeDecisionOptions& options);

}  // namespace colmap_gcn

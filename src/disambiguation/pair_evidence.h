#pragma once

#include <map>
#include <vector>

#include <Eigen/Core>

#include "disambiguation/inlier_grid.h"
#include "disambiguation/lookalike_decision.h"
#include "disambiguation/relative_pose.h"
#include "scene/two_view_geometry_store.h"

namespace colmap_gcn {

// The relative rotations (x2 = R x1 + t) a verified pair's geometry gives.
struct PairRotations {
  // From E (or F and the intrinsics), disambiguated by cheirality.
  bool has_essential = false;
  Eigen::Matrix3d essential = Eigen::Matrix3d::Identity();
  // The decompositions of its homography that pass the cheirality test.
  std::vector<Eigen::Matrix3d> homography;
};

// What the pair evidence is measured with: per image (index), its camera
// and keypoint positions; per camera, its intrinsics and whether COLMAP's E
// holds for it (its focal length is the one COLMAP verified with).
struct PairEvidenceCameras {
  std::vector<camera_t> image_cameras;
  const std::vector<KeypointPositions>* keypoints = nullptr;
  std::map<camera_t, PinholeIntrinsics> intrinsics;
  std::map<camera_t, bool> use_colmap_E;
};

// For every pair p with measure[p]: its rotations (E or F with the
// intrinsics, and the homography's decompositions, disambiguated by
// cheirality on at most max_rays inlier rays) into (*rotations)[p], and the
// edge's rotation, alternatives and mean view rays into (*edges)[p], whose
// image indices must be set. Other pairs are left as they are. The result
// does not depend on num_threads.
void MeasurePairEvidence(const std::vector<VerifiedTwoViewGeometry>& pairs,
                         const PairEvidenceCameras& cameras,
                         const std::vector<bool>& measure,
                         int max_rays,
                         int num_threads,
                         std::vector<ViewGraphEdge>* edges,
                         std::vector<PairRotations>* rotations);

}  // namespace colmap_gcn

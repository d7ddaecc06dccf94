#include "disambiguation/pair_evidence.h"

#include <algorithm>

#include <Eigen/Geometry>

#include "util/threading.h"

namespace colmap_gcn {
namespace {

// Rays (normalised coordinates) of at most max_rays of a pair's inliers,
// evenly spaced over them.
void InlierRays(const VerifiedTwoViewGeometry& pair,
                const KeypointPositions& keypoints1,
                const KeypointPositions& keypoints2,
                const PinholeIntrinsics& camera1,
                const PinholeIntrinsics& camera2,
                const int max_rays,
                Eigen::Matrix2Xd* rays1,
                Eigen::Matrix2Xd* rays2) {
  const Eigen::Index num_inliers = pair.inliers.rows();
  const Eigen::Index n = std::min<Eigen::Index>(num_inliers, max_rays);
  rays1->resize(2, n);
  rays2->resize(2, n);
  Eigen::Index used = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index row = i * num_inliers / n;
    const uint32_t k1 = pair.inliers(row, 0);
    const uint32_t k2 = pair.inliers(row, 1);
    if (k1 >= keypoints1.rows() || k2 >= keypoints2.rows()) continue;
    rays1->col(used) << (keypoints1(k1, 0) - camera1.cx) / camera1.fx,
        (keypoints1(k1, 1) - camera1.cy) / camera1.fy;
    rays2->col(used) << (keypoints2(k2, 0) - camera2.cx) / camera2.fx,
        (keypoints2(k2, 1) - camera2.cy) / camera2.fy;
    ++used;
  }
  rays1->conservativeResize(2, used);
  rays2->conservativeResize(2, used);
}

// The relative rotations a pair's geometry gives: from E when COLMAP
// verified it calibrated with trusted focal lengths (use_E), otherwise from
// F and the cameras' (possibly self-calibrated) intrinsics; and the
// candidates its homography allows.
void MeasureRotations(const VerifiedTwoViewGeometry& pair,
                      const PinholeIntrinsics& camera1,
                      const PinholeIntrinsics& camera2,
                      const bool use_E,
                      const Eigen::Matrix2Xd& rays1,
                      const Eigen::Matrix2Xd& rays2,
                      PairRotations* rotations) {
  Eigen::Matrix3d E = pair.E;
  const bool has_E = pair.config == 2 && E.norm() >= 1e-12;
  bool has_essential = true;
  if (!(use_E && has_E)) {
    if (pair.F.norm() >= 1e-12) {
      E = camera2.K().transpose() * pair.F * camera1.K();
    } else if (!has_E) {
      has_essential = false;
    }
  }
  rotations->has_essential =
      has_essential &&
      RotationFromEssential(E, rays1, rays2, &rotations->essential);
  if (pair.H.norm() >= 1e-12) {
    const Eigen::Matrix3d H = camera2.K().inverse() * pair.H * camera1.K();
    rotations->homography = RotationsFromHomography(H, rays1, rays2);
  }
}

// The mean direction of the inlier rays in each camera (the parallax test,
// lookalike_decision.h).
void MeanViewRays(const Eigen::Matrix2Xd& rays1,
                  const Eigen::Matrix2Xd& rays2,
                  ViewGraphEdge* edge) {
  if (rays1.cols() == 0) return;
  Eigen::Vector3d sum1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum2 = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < rays1.cols(); ++i) {
    sum1 += rays1.col(i).homogeneous().normalized();
    sum2 += rays2.col(i).homogeneous().normalized();
  }
  edge->has_view_rays = true;
  edge->view_ray1 = sum1.normalized();
  edge->view_ray2 = sum2.normalized();
}

// Which of a pair's rotations the tree may chain: a planar or panoramic
// pair's (config 4-6) F does not determine the rotation, its homography
// does when only one decomposition passes the cheirality test; a general
// pair's comes from E (or F). Every other rotation the geometry allows is
// an alternative for the loop test.
void AssignRotations(const int config,
                     const PairRotations& rotations,
                     ViewGraphEdge* edge) {
  const bool planar = config >= 4 && config <= 6;
  edge->alternatives.clear();
  if (planar && rotations.homography.size() == 1) {
    edge->has_rotation = true;
    edge->rotation = rotations.homography[0];
    if (rotations.has_essential) {
      edge->alternatives.push_back(rotations.essential);
    }
    return;
  }
  edge->has_rotation = !planar && rotations.has_essential;
  if (edge->has_rotation) {
    edge->rotation = rotations.essential;
  } else if (rotations.has_essential) {
    edge->alternatives.push_back(rotations.essential);
  }
  edge->alternatives.insert(edge->alternatives.end(),
                            rotations.homography.begin(),
                            rotations.homography.end());
}

}  // namespace

void MeasurePairEvidence(const std::vector<VerifiedTwoViewGeometry>& pairs,
                         const PairEvidenceCameras& cameras,
                         const std::vector<bool>& measure,
                         const int max_rays,
                         const int num_threads,
                         std::vector<ViewGraphEdge>* edges,
                         std::vector<PairRotations>* rotations) {
  ParallelFor(0, static_cast<int>(pairs.size()), num_threads, [&](int p) {
    if (!measure[p]) return;
    const VerifiedTwoViewGeometry& pair = pairs[p];
    ViewGraphEdge& edge = (*edges)[p];
    const camera_t camera1 = cameras.image_cameras[edge.image1];
    const camera_t camera2 = cameras.image_cameras[edge.image2];
    const PinholeIntrinsics& intrinsics1 = cameras.intrinsics.at(camera1);
    const PinholeIntrinsics& intrinsics2 = cameras.intrinsics.at(camera2);
    Eigen::Matrix2Xd rays1;
    Eigen::Matrix2Xd rays2;
    InlierRays(pair,
               (*cameras.keypoints)[edge.image1],
               (*cameras.keypoints)[edge.image2],
               intrinsics1,
               intrinsics2,
               max_rays,
               &rays1,
               &rays2);
    (*rotations)[p] = PairRotations();
    MeasureRotations(
        pair,
        intrinsics1,
        intrinsics2,
        cameras.use_colmap_E.at(camera1) && cameras.use_colmap_E.at(camera2),
        rays1,
        rays2,
        &(*rotations)[p]);
    AssignRotations(pair.config, (*rotations)[p], &edge);
    MeanViewRays(rays1, rays2, &edge);
  });
}

}  // namespace colmap_gcn

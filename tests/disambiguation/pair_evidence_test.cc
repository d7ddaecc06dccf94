// The evidence of single pairs: rotations from E or from F with given
// intrinsics, and which pairs are measured.

#include "disambiguation/pair_evidence.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

namespace colmap_gcn {
namespace {

constexpr double kFocal = 600;

double AngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle() * 180.0 / M_PI;
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Two cameras 20 degrees apart looking at points in front of both: the
// pair's inliers, keypoints, E and F, written with `focal`.
struct TwoViews {
  std::vector<VerifiedTwoViewGeometry> pairs;
  std::vector<KeypointPositions> keypoints;
  Eigen::Matrix3d R;
};

TwoViews MakeTwoViews(double focal) {
  TwoViews views;
  views.R = Eigen::AngleAxisd(20 * M_PI / 180, Eigen::Vector3d::UnitY())
                .toRotationMatrix();
  const Eigen::Vector3d t(-1, 0, 0.2);
  Eigen::Matrix3d K;
  K << focal, 0, 320, 0, focal, 240, 0, 0, 1;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-1, 1);
  const int n = 80;
  views.keypoints.assign(2, KeypointPositions(n, 2));
  VerifiedTwoViewGeometry pair;
  pair.pair_id = 1;
  pair.image_id1 = 1;
  pair.image_id2 = 2;
  pair.config = 2;
  pair.inliers.resize(n, 2);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d X(uniform(rng), uniform(rng), 5 + uniform(rng));
    const Eigen::Vector3d x1 = K * X;
    const Eigen::Vector3d x2 = K * (views.R * X + t);
    views.keypoints[0].row(i) << x1.x() / x1.z(), x1.y() / x1.z();
    views.keypoints[1].row(i) << x2.x() / x2.z(), x2.y() / x2.z();
    pair.inliers.row(i) << i, i;
  }
  pair.E = Skew(t) * views.R;
  pair.F = K.transpose().inverse() * pair.E * K.inverse();
  views.pairs.push_back(pair);
  return views;
}

PairEvidenceCameras Cameras(const TwoViews& views,
                            double focal,
                            bool use_colmap_E) {
  PairEvidenceCameras cameras;
  cameras.image_cameras = {1, 2};
  cameras.keypoints = &views.keypoints;
  for (const camera_t camera : {1, 2}) {
    cameras.intrinsics[camera] = PinholeIntrinsics{focal, focal, 320, 240};
    cameras.use_colmap_E[camera] = use_colmap_E;
  }
  return cameras;
}

TEST(PairEvidence, RecoversTheRotationFromEAndFromF) {
  const TwoViews views = MakeTwoViews(kFocal);
  for (const bool use_colmap_E : {true, false}) {
    std::vector<ViewGraphEdge> edges(1);
    edges[0].image1 = 0;
    edges[0].image2 = 1;
    std::vector<PairRotations> rotations(1);
    MeasurePairEvidence(views.pairs,
                        Cameras(views, kFocal, use_colmap_E),
                        {true},
                        200,
                        1,
                        &edges,
                        &rotations);
    ASSERT_TRUE(rotations[0].has_essential);
    ASSERT_TRUE(edges[0].has_rotation);
    EXPECT_LT(AngleBetween(edges[0].rotation, views.R), 0.1);
  }
}

// With F, the rotation follows the intrinsics it is measured with: a focal
// length off by 1.5 turns it the wrong amount (with the right one it is
// exact, above). Pairs not to be measured are left as they are.
TEST(PairEvidence, TheRotationFromFFollowsTheFocalLength) {
  const TwoViews views = MakeTwoViews(kFocal);
  std::vector<ViewGraphEdge> edges(1);
  edges[0].image1 = 0;
  edges[0].image2 = 1;
  std::vector<PairRotations> rotations(1);
  MeasurePairEvidence(views.pairs,
                      Cameras(views, kFocal / 1.5, false),
                      {false},
                      200,
                      1,
                      &edges,
                      &rotations);
  EXPECT_FALSE(edges[0].has_rotation);
  EXPECT_FALSE(rotations[0].has_essential);
  MeasurePairEvidence(views.pairs,
                      Cameras(views, kFocal / 1.5, false),
                      {true},
                      200,
                      1,
                      &edges,
                      &rotations);
  ASSERT_TRUE(edges[0].has_rotation);
  EXPECT_GT(AngleBetween(edges[0].rotation, views.R), 2.0);
}

}  // namespace
}  // namespace colmap_gcn

#include "disambiguation/focal_calibration.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <Eigen/LU>

namespace colmap_gcn {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

PinholeIntrinsics Camera(double focal) {
  PinholeIntrinsics camera;
  camera.fx = camera.fy = focal;
  camera.cx = 320;
  camera.cy = 240;
  return camera;
}

// Cameras on a ring around the origin looking inwards (world-to-camera
// rotations R_i, centres c_i), with a little deterministic jitter; the F of
// every pair up to 3 steps apart with the true focal length.
struct Ring {
  std::vector<Eigen::Matrix3d> rotations;
  std::vector<Eigen::Vector3d> centres;
};

Ring MakeRing(int n, uint64_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> jitter(0.0, 0.05);
  Ring ring;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    const Eigen::Vector3d centre(4 * std::cos(a), jitter(rng), 4 * std::sin(a));
    const Eigen::Vector3d z = (-centre).normalized();
    const Eigen::Vector3d x = Eigen::Vector3d::UnitY().cross(z).normalized();
    Eigen::Matrix3d camera_to_world;
    camera_to_world << x, z.cross(x), z;
    const Eigen::Matrix3d tilt =
        Eigen::AngleAxisd(jitter(rng), Eigen::Vector3d::UnitX())
            .toRotationMatrix();
    ring.rotations.push_back(tilt * camera_to_world.transpose());
    ring.centres.push_back(centre);
  }
  return ring;
}

std::vector<FundamentalPair> Fundamentals(const Ring& ring,
                                          const std::vector<int>& camera_of,
                                          double true_focal) {
  const Eigen::Matrix3d Kinv = Camera(true_focal).K().inverse();
  std::vector<FundamentalPair> pairs;
  const int n = static_cast<int>(ring.rotations.size());
  for (int i = 0; i < n; ++i) {
    for (int d = 1; d <= 3; ++d) {
      const int j = (i + d) % n;
      const Eigen::Matrix3d R =
          ring.rotations[j] * ring.rotations[i].transpose();
      const Eigen::Vector3d t =
          ring.rotations[j] * (ring.centres[i] - ring.centres[j]);
      FundamentalPair pair;
      pair.camera1 = camera_of[i];
      pair.camera2 = camera_of[j];
      pair.F = Kinv.transpose() * Skew(t) * R * Kinv;
      pairs.push_back(pair);
    }
  }
  return pairs;
}

TEST(FocalCalibration, EssentialMatrixIsConsistent) {
  const Ring ring = MakeRing(6, 1);
  const std::vector<FundamentalPair> pairs =
      Fundamentals(ring, {0, 0, 0, 0, 0, 0}, 640);
  const Eigen::Matrix3d K = Camera(640).K();
  EXPECT_LT(EssentialInconsistency(K.transpose() * pairs[0].F * K), 1e-9);
  const Eigen::Matrix3d wrong = Camera(768).K();
  EXPECT_GT(EssentialInconsistency(wrong.transpose() * pairs[0].F * wrong),
            1e-4);
  EXPECT_EQ(EssentialInconsistency(Eigen::Matrix3d::Zero()), 1);
}

TEST(FocalCalibration, RecoversSharedScaleOfOneCameraPerImage) {
  const int n = 20;
  const Ring ring = MakeRing(n, 2);
  std::vector<int> camera_of(n);
  for (int i = 0; i < n; ++i) camera_of[i] = i;
  const std::vector<FundamentalPair> pairs = Fundamentals(ring, camera_of, 640);
  // The database's guess: 1.2 x the true focal length, no trusted prior.
  const std::vector<PinholeIntrinsics> cameras(n, Camera(1.2 * 640));
  const FocalCalibrationResult result =
      SelfCalibrateFocalLengths(cameras,
                                std::vector<bool>(n, false),
                                std::vector<int>(n, 1),
                                pairs,
                                FocalCalibrationOptions());
  for (int c = 0; c < n; ++c) {
    EXPECT_NEAR(result.cameras[c].fx, 640, 0.02 * 640) << c;
    EXPECT_EQ(result.cameras[c].fx, result.cameras[c].fy);
    EXPECT_EQ(result.cameras[c].cx, 320);
  }
  EXPECT_LT(result.cost_after, result.cost_before);
}

TEST(FocalCalibration, RecoversFocalOfASharedCameraAndKeepsTrustedOnes) {
  const int n = 16;
  const Ring ring = MakeRing(n, 3);
  // Images 0..11 share camera 0 (guessed 1.2x too long); images 12..15 have
  // camera 1 with a trusted, right focal length.
  std::vector<int> camera_of(n, 0);
  for (int i = 12; i < n; ++i) camera_of[i] = 1;
  const std::vector<FundamentalPair> pairs = Fundamentals(ring, camera_of, 500);
  const FocalCalibrationResult result =
      SelfCalibrateFocalLengths({Camera(600), Camera(500)},
                                {false, true},
                                {12, 4},
                                pairs,
                                FocalCalibrationOptions());
  EXPECT_NEAR(result.cameras[0].fx, 500, 0.02 * 500);
  EXPECT_EQ(result.cameras[1].fx, 500);
  EXPECT_EQ(result.scales[1], 1);
}

TEST(FocalCalibration, DeclinesWithoutEvidence) {
  const Ring ring = MakeRing(4, 4);
  std::vector<FundamentalPair> pairs = Fundamentals(ring, {0, 1, 2, 3}, 640);
  pairs.resize(3);  // fewer than min_num_pairs
  const std::vector<PinholeIntrinsics> cameras(4, Camera(768));
  FocalCalibrationResult result =
      SelfCalibrateFocalLengths(cameras,
                                std::vector<bool>(4, false),
                                std::vector<int>(4, 1),
                                pairs,
                                FocalCalibrationOptions());
  for (const PinholeIntrinsics& camera : result.cameras) {
    EXPECT_EQ(camera.fx, 768);
  }
  // A criterion without a minimum inside the range: the true focal length
  // lies far outside it.
  const Ring wide = MakeRing(12, 5);
  std::vector<int> camera_of(12);
  for (int i = 0; i < 12; ++i) camera_of[i] = i;
  pairs = Fundamentals(wide, camera_of, 640);
  result =
      SelfCalibrateFocalLengths(std::vector<PinholeIntrinsics>(12, Camera(64)),
                                std::vector<bool>(12, false),
                                std::vector<int>(12, 1),
                                pairs,
                                FocalCalibrationOptions());
  EXPECT_EQ(result.scales[0], 1);
}

TEST(FocalCalibration, BadInputNamesTheProblem) {
  FocalCalibrationOptions options;
  options.max_scale = 0.1;
  EXPECT_THROW(options.Check(), std::exception);
  EXPECT_THROW(
      SelfCalibrateFocalLengths(
          {Camera(1)}, {false, true}, {1}, {}, FocalCalibrationOptions()),
      std::exception);
}

}  // namespace
}  // namespace colmap_gcn

#include "evaluation/pose_pair_filter.h"

#include <cmath>

#include <gtest/gtest.h>

#include "scene/camera_models.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

constexpr double kPi = 3.14159265358979323846;

// PINHOLE f = 100 on a 100 x 100 image, principal point at the centre:
// corner rays at atan(sqrt(0.5)) = 35.26 degrees from the axis.
ModelCamera MakeCamera(camera_t id, const std::string& model = "PINHOLE") {
  ModelCamera camera;
  camera.camera_id = id;
  camera.model_id = CameraModelNameToId(model);
  camera.width = 100;
  camera.height = 100;
  camera.params = {100, 100, 50, 50};
  if (model == "OPENCV_FISHEYE") camera.params = {100, 100, 50, 50, 0, 0, 0, 0};
  return camera;
}

// Camera at centre looking along axis (unit), y up.
ModelImage MakeImage(image_t id,
                     const Eigen::Vector3d& centre,
                     const Eigen::Vector3d& axis) {
  const Eigen::Vector3d z = axis.normalized();
  const Eigen::Vector3d y(0, 1, 0);
  const Eigen::Vector3d x = y.cross(z);
  Eigen::Matrix3d rotation;
  rotation.row(0) = x.transpose();
  rotation.row(1) = y.transpose();
  rotation.row(2) = z.transpose();
  const Eigen::Quaterniond q(rotation);
  ModelImage image;
  image.image_id = id;
  image.camera_id = 1;
  image.name = "img" + std::to_string(id);
  image.qvec = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  image.tvec = -rotation * centre;
  return image;
}

// n cameras evenly on a horizontal ring of radius 5, all facing its centre:
// cameras s steps apart have optical axes s * 360 / n degrees apart.
Reconstruction MakeRing(int n) {
  Reconstruction model;
  model.cameras[1] = MakeCamera(1);
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * kPi * i / n;
    const Eigen::Vector3d centre(5 * std::sin(phi), 0, 5 * std::cos(phi));
    model.images[i + 1] = MakeImage(i + 1, centre, -centre);
  }
  return model;
}

TEST(PosePairFilter, MaxRayAngleAtTheCorner) {
  EXPECT_NEAR(MaxRayAngleFromAxis(MakeCamera(1)) * 180 / kPi,
              std::atan(std::sqrt(0.5)) * 180 / kPi,
              1e-9);
  // An off-centre principal point: the farthest corner counts.
  ModelCamera shifted = MakeCamera(1);
  shifted.params = {100, 100, 0, 0};
  EXPECT_NEAR(MaxRayAngleFromAxis(shifted), std::atan(std::sqrt(2.0)), 1e-9);
  ModelCamera simple = MakeCamera(1, "SIMPLE_RADIAL");
  simple.params = {100, 50, 50, 0.01};
  EXPECT_NEAR(MaxRayAngleFromAxis(simple), std::atan(std::sqrt(0.5)), 1e-9);
  EXPECT_NEAR(MaxRayAngleFromAxis(MakeCamera(1, "OPENCV_FISHEYE")), kPi, 0);
}

TEST(PosePairFilter, BoundIsAxisAngleMinusBothHalfFields) {
  const ModelCamera camera = MakeCamera(1);
  const double half = std::atan(std::sqrt(0.5)) * 180 / kPi;
  const ModelImage front = MakeImage(1, {0, 0, -5}, {0, 0, 1});
  const ModelImage facing = MakeImage(2, {0, 0, 5}, {0, 0, -1});
  const ModelImage side = MakeImage(3, {5, 0, 0}, {-1, 0, 0});
  const ModelImage same = MakeImage(4, {1, 0, -5}, {0, 0, 1});
  EXPECT_NEAR(MinViewpointChangeDeg(front, camera, facing, camera),
              180 - 2 * half,
              1e-6);
  EXPECT_NEAR(
      MinViewpointChangeDeg(front, camera, side, camera), 90 - 2 * half, 1e-6);
  // Parallel axes: no bound (the rule never skips such a pair).
  EXPECT_EQ(MinViewpointChangeDeg(front, camera, same, camera), 0.0);
}

TEST(PosePairFilter, RingKeepsNeighboursAndSkipsOppositeViews) {
  const Reconstruction ring = MakeRing(8);  // steps of 45 degrees
  PosePairFilterOptions options;
  // Disabled: every pair.
  PosePairSelection all = SelectPosePairs(ring, options);
  EXPECT_EQ(all.num_images, 8u);
  EXPECT_EQ(all.kept.size(), 28u);
  EXPECT_EQ(all.num_skipped, 0u);

  // Bound = axis angle - 70.53: at 70 only the 4 opposite pairs (180).
  options.max_viewpoint_change_deg = 70;
  const PosePairSelection opposite = SelectPosePairs(ring, options);
  EXPECT_EQ(opposite.kept.size(), 24u);
  EXPECT_EQ(opposite.num_skipped, 4u);
  for (const auto& [name1, name2] : opposite.kept) {
    EXPECT_LT(name1, name2);
    const int i = std::stoi(name1.substr(3));
    const int j = std::stoi(name2.substr(3));
    EXPECT_NE(std::abs(i - j), 4) << name1 << " " << name2;
  }

  // At 30: also 135 degrees (3 steps: 8 pairs) is beyond 100.53.
  options.max_viewpoint_change_deg = 30;
  const PosePairSelection tight = SelectPosePairs(ring, options);
  EXPECT_EQ(tight.kept.size(), 16u);
  EXPECT_EQ(tight.num_skipped, 12u);
}

TEST(PosePairFilter, FisheyeCamerasAreNeverSkipped) {
  Reconstruction ring = MakeRing(8);
  ring.cameras[1] = MakeCamera(1, "OPENCV_FISHEYE");
  PosePairFilterOptions options;
  options.max_viewpoint_change_deg = 1;
  EXPECT_EQ(SelectPosePairs(ring, options).num_skipped, 0u);
}

TEST(PosePairFilter, RejectsBadOptionsAndMissingCameras) {
  PosePairFilterOptions options;
  EXPECT_NO_THROW(options.Check());
  options.max_viewpoint_change_deg = -1;
  try {
    options.Check();
    ADD_FAILURE() << "-1 degrees accepted";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(),
                 "max_viewpoint_change_deg must be in [0, 180] (got -1)");
  }
  EXPECT_THROW(SelectPosePairs(MakeRing(3), options), Error);
  options.max_viewpoint_change_deg = 70;
  Reconstruction ring = MakeRing(3);
  ring.cameras.clear();
  EXPECT_THROW(SelectPosePairs(ring, options), Error);
}

}  // namespace
}  // namespace colmap_gcn

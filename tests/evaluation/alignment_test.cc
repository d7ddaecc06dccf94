#include "evaluation/alignment.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

namespace colmap_gcn {
namespace {

// A camera at `centre` looking at the origin (world-to-camera pose).
ModelImage LookAtOrigin(image_t id, const Eigen::Vector3d& centre) {
  const Eigen::Vector3d z = (-centre).normalized();
  Eigen::Vector3d x = Eigen::Vector3d::UnitZ().cross(z);
  if (x.norm() < 1e-9) x = Eigen::Vector3d::UnitX();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d rotation;
  rotation.row(0) = x;
  rotation.row(1) = y;
  rotation.row(2) = z;
  ModelImage image;
  image.image_id = id;
  image.camera_id = 1;
  image.name = "img" + std::to_string(id) + ".jpg";
  const Eigen::Quaterniond q(rotation);
  image.qvec << q.w(), q.x(), q.y(), q.z();
  image.tvec = -rotation * centre;
  return image;
}

// n cameras on a ring of radius 5 (with some height variation).
Reconstruction Ring(int n) {
  Reconstruction model;
  model.cameras[1].camera_id = 1;
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * M_PI * i / n;
    const Eigen::Vector3d centre(
        5 * std::cos(angle), 5 * std::sin(angle), 0.5 * std::sin(3 * angle));
    model.images[i + 1] = LookAtOrigin(i + 1, centre);
  }
  return model;
}

// Applies x' = s R x + t to a model's cameras.
Reconstruction Transform(const Reconstruction& model, const Similarity3d& sim) {
  Reconstruction out = model;
  for (auto& [id, image] : out.images) {
    const Eigen::Vector3d centre = sim.Transform(image.ProjectionCenter());
    const Eigen::Matrix3d rotation =
        image.RotationMatrix() * sim.rotation.transpose();
    const Eigen::Quaterniond q(rotation);
    image.qvec << q.w(), q.x(), q.y(), q.z();
    image.tvec = -rotation * centre;
  }
  return out;
}

TEST(PoseErrors, ExactModelUnderSimilarityHasNoError) {
  const Reconstruction gt = Ring(12);
  Similarity3d sim;
  sim.scale = 0.3;
  sim.rotation = Eigen::AngleAxisd(2.0, Eigen::Vector3d(0, 1, 1).normalized())
                     .toRotationMatrix();
  sim.translation = Eigen::Vector3d(4, 5, 6);
  Reconstruction model = Transform(gt, sim);
  model.images.erase(3);  // one image not registered
  const PoseErrors errors = ComputePoseErrors(model, gt, PoseErrorOptions());
  ASSERT_TRUE(errors.aligned);
  EXPECT_EQ(errors.num_gt_images, 12u);
  EXPECT_EQ(errors.num_evaluated, 11u);
  EXPECT_NEAR(errors.scene_extent, CameraExtent(gt), 1e-12);
  EXPECT_LT(errors.median_rotation_error_deg, 1e-6);
  EXPECT_LT(errors.median_position_error, 1e-9);
  EXPECT_NEAR(errors.model_to_gt.scale, 1 / 0.3, 1e-9);
  EXPECT_DOUBLE_EQ(errors.fraction_accurate, 11.0 / 12.0);
}

TEST(PoseErrors, FoldedModelShowsLargeErrors) {
  // The back half of the ring registered onto the front half (mirrored
  // across the x = 0 plane and turned to face the same facade), as repeated
  // structure folds a model: every image registers, but one similarity
  // cannot fit both halves.
  const Reconstruction gt = Ring(16);
  Reconstruction folded;
  folded.cameras = gt.cameras;
  for (const auto& [id, image] : gt.images) {
    Eigen::Vector3d centre = image.ProjectionCenter();
    if (centre.x() < 0) centre.x() = -centre.x();
    folded.images[id] = LookAtOrigin(id, centre);
    folded.images[id].name = image.name;
  }
  const PoseErrors errors = ComputePoseErrors(folded, gt, PoseErrorOptions());
  ASSERT_TRUE(errors.aligned);
  EXPECT_EQ(errors.num_evaluated, 16u);
  // The folded half faces the wrong way: large rotation errors there, and
  // the compromise alignment shifts every camera.
  EXPECT_GT(errors.median_position_error, 0.1);
  EXPECT_GT(*std::max_element(errors.rotation_errors_deg.begin(),
                              errors.rotation_errors_deg.end()),
            90.0);
  size_t num_large_rotation = 0;
  for (const double error : errors.rotation_errors_deg) {
    num_large_rotation += error > 20.0 ? 1 : 0;
  }
  EXPECT_GE(num_large_rotation, 4u);
  EXPECT_LT(errors.fraction_accurate, 0.5);
  // The ring covers all of its circle; the folded one half of it.
  EXPECT_NEAR(errors.gt_ring_coverage, 15.0 / 16.0, 0.01);
  EXPECT_LT(errors.ring_coverage, 0.6);
}

TEST(RingCoverage, MeasuresTheLargestGap) {
  std::vector<Eigen::Vector3d> centres;
  // Three quarters of a tilted circle, every 10 degrees.
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (int degrees = 0; degrees <= 270; degrees += 10) {
    const double a = degrees * M_PI / 180.0;
    centres.push_back(tilt * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0) +
                      Eigen::Vector3d(5, -2, 1));
  }
  EXPECT_NEAR(RingCoverage(centres), 0.75, 1e-9);
  centres.resize(2);
  EXPECT_EQ(RingCoverage(centres), -1);
}

TEST(RotationAngleDeg, KnownAngle) {
  const Eigen::Matrix3d a =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d b =
      Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(RotationAngleDeg(a, b), 0.2 * 180 / M_PI, 1e-9);
}

}  // namespace
}  // namespace colmap_gcn

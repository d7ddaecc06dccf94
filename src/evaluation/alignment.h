#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "math/similarity_transform.h"
#include "scene/reconstruction.h"

namespace colmap_gcn {

struct PoseErrorOptions {
  // An image is accurate when its rotation error is below this (degrees) ...
  double max_rotation_error_deg = 5.0;
  // ... and its position error below this fraction of the scene extent.
  double max_position_error = 0.05;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// Camera errors of a model against ground truth after aligning the camera
// centres with one similarity. The alignment uses every image in both, so a
// folded model (back side registered onto the front) cannot be aligned well
// and shows large errors even though every image registered.
struct PoseErrors {
  size_t num_gt_images = 0;               // images with ground truth
  size_t num_evaluated = 0;               // of those, registered in the model
  bool aligned = false;                   // a similarity could be estimated
  double scene_extent = 0;                // largest distance between GT centres
  double median_rotation_error_deg = -1;  // over evaluated images
  double median_position_error = -1;      // relative to scene_extent
  // Fractions over all GT images (unregistered images count as failures).
  double fraction_rotation_ok = 0;
  double fraction_position_ok = 0;
  double fraction_accurate = 0;  // both
  // Per evaluated image, in name order.
  std::vector<std::string> names;
  std::vector<double> rotation_errors_deg;
  std::vector<double> position_errors;
  Similarity3d model_to_gt;
  // RingCoverage of the evaluated images' centres in the model and of every
  // ground-truth image's: for cameras orbiting an object (ground truth near
  // 1), a model folded onto one side covers far less of the circle.
  double ring_coverage = -1;
  double gt_ring_coverage = -1;
};

PoseErrors ComputePoseErrors(const Reconstruction& model,
                             const Reconstruction& ground_truth,
                             const PoseErrorOptions& options);

// The fraction of a circle camera centres cover around their centroid: the
// centres projected onto their best-fit plane (the two largest principal
// directions), one minus the largest angular gap between neighbouring
// centres over 360 degrees. -1 for fewer than 3 centres or no spread.
double RingCoverage(const std::vector<Eigen::Vector3d>& centres);

// Largest distance between two camera centres of a model.
double CameraExtent(const Reconstruction& reconstruction);

// Angle of the rotation R_a R_b^T in degrees.
double RotationAngleDeg(const Eigen::Matrix3d& rotation_a,
                        const Eigen::Matrix3d& rotation_b);

}  // namespace colmap_gcn

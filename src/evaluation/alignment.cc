#include "evaluation/alignment.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "util/option_check.h"

namespace colmap_gcn {
namespace {

double Median(std::vector<double> values) {
  if (values.empty()) return -1;
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  double median = values[mid];
  if (values.size() % 2 == 0) {
    median = 0.5 *
             (median + *std::max_element(values.begin(), values.begin() + mid));
  }
  return median;
}

}  // namespace

void PoseErrorOptions::Check() const {
  CHECK_OPTION_GT(max_rotation_error_deg, 0.0);
  CHECK_OPTION_GT(max_position_error, 0.0);
}

double RotationAngleDeg(const Eigen::Matrix3d& rotation_a,
                        const Eigen::Matrix3d& rotation_b) {
  const Eigen::Matrix3d relative = rotation_a * rotation_b.transpose();
  const double cos_angle =
      std::clamp((relative.trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(cos_angle) * 180.0 / M_PI;
}

double CameraExtent(const Reconstruction& reconstruction) {
  std::vector<Eigen::Vector3d> centres;
  for (const auto& [image_id, image] : reconstruction.images) {
    centres.push_back(image.ProjectionCenter());
  }
  double extent = 0;
  for (size_t i = 0; i < centres.size(); ++i) {
    for (size_t j = i + 1; j < centres.size(); ++j) {
      extent = std::max(extent, (centres[i] - centres[j]).norm());
    }
  }
  return extent;
}

PoseErrors ComputePoseErrors(const Reconstruction& model,
                             const Reconstruction& ground_truth,
                             const PoseErrorOptions& options) {
  PoseErrors errors;
  errors.num_gt_images = ground_truth.images.size();
  errors.scene_extent = CameraExtent(ground_truth);

  // Common images by name, in name order (deterministic).
  std::map<std::string, std::pair<const ModelImage*, const ModelImage*>> common;
  for (const auto& [image_id, gt_image] : ground_truth.images) {
    const image_t model_id = model.FindImageWithName(gt_image.name);
    if (model_id != kInvalidImageId) {
      common[gt_image.name] = {&model.images.at(model_id), &gt_image};
    }
  }
  errors.num_evaluated = common.size();
  std::vector<Eigen::Vector3d> src;
  std::vector<Eigen::Vector3d> dst;
  for (const auto& [name, images] : common) {
    src.push_back(images.first->ProjectionCenter());
    dst.push_back(images.second->ProjectionCenter());
  }
  errors.aligned = EstimateSimilarity(src, dst, &errors.model_to_gt);
  if (!errors.aligned || errors.scene_extent <= 0) {
    errors.aligned = false;
    return errors;
  }
  const Similarity3d& sim = errors.model_to_gt;
  size_t num_rotation_ok = 0;
  size_t num_position_ok = 0;
  size_t num_accurate = 0;
  for (const auto& [name, images] : common) {
    // World-to-camera rotation of the model image expressed in the GT
    // frame: x_cam = R_i x_model = R_i R_sim^T (x_gt - t) / s.
    const Eigen::Matrix3d rotation =
        images.first->RotationMatrix() * sim.rotation.transpose();
    const double rotation_error =
        RotationAngleDeg(images.second->RotationMatrix(), rotation);
    const double position_error =
        (sim.Transform(images.first->ProjectionCenter()) -
         images.second->ProjectionCenter())
            .norm() /
        errors.scene_extent;
    errors.names.push_back(name);
    errors.rotation_errors_deg.push_back(rotation_error);
    errors.position_errors.push_back(position_error);
    const bool rotation_ok = rotation_error <= options.max_rotation_error_deg;
    const bool position_ok = position_error <= options.max_position_error;
    num_rotation_ok += rotation_ok ? 1 : 0;
    num_position_ok += position_ok ? 1 : 0;
    num_accurate += rotation_ok && position_ok ? 1 : 0;
  }
  errors.median_rotation_error_deg = Median(errors.rotation_errors_deg);
  errors.median_position_error = Median(errors.position_errors);
  if (errors.num_gt_images > 0) {
    const double n = static_cast<double>(errors.num_gt_images);
    errors.fraction_rotation_ok = num_rotation_ok / n;
    errors.fraction_position_ok = num_position_ok / n;
    errors.fraction_accurate = num_accurate / n;
  }
  return errors;
}

}  // namespace colmap_gcn

#include "evaluation/alignment.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

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

double RingCoverage(const std::vector<Eigen::Vector3d>& centres) {
  if (centres.size() < 3) return -1;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& c : centres) mean += c;
  mean /= static_cast<double>(centres.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& c : centres) {
    scatter += (c - mean) * (c - mean).transpose();
  }
  // Eigenvalues ascending: the last two columns span the ring's plane.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  if (!(solver.eigenvalues()(2) > 0)) return -1;
  const Eigen::Vector3d u = solver.eigenvectors().col(2);
  const Eigen::Vector3d v = solver.eigenvectors().col(1);
  // The circle through them in that plane (algebraic least squares:
  // x^2 + y^2 + D x + E y + F = 0); its centre, not the centroid, so that
  // an arc covers what it spans.
  const int n = static_cast<int>(centres.size());
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d d = centres[i] - mean;
    A.row(i) << d.dot(u), d.dot(v), 1.0;
    b(i) = -(d.dot(u) * d.dot(u) + d.dot(v) * d.dot(v));
  }
  const Eigen::Vector3d circle = A.colPivHouseholderQr().solve(b);
  Eigen::Vector2d centre = -0.5 * circle.head<2>();
  if (!centre.allFinite()) centre.setZero();
  std::vector<double> azimuths;
  for (const Eigen::Vector3d& c : centres) {
    const Eigen::Vector2d d =
        Eigen::Vector2d((c - mean).dot(u), (c - mean).dot(v)) - centre;
    if (d.x() == 0 && d.y() == 0) continue;
    azimuths.push_back(std::atan2(d.y(), d.x()));
  }
  if (azimuths.size() < 3) return -1;
  std::sort(azimuths.begin(), azimuths.end());
  double largest_gap = azimuths.front() + 2 * M_PI - azimuths.back();
  for (size_t i = 1; i < azimuths.size(); ++i) {
    largest_gap = std::max(largest_gap, azimuths[i] - azimuths[i - 1]);
  }
  return 1.0 - largest_gap / (2 * M_PI);
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
  errors.ring_coverage = RingCoverage(src);
  std::vector<Eigen::Vector3d> gt_centres;
  for (const auto& [image_id, gt_image] : ground_truth.images) {
    gt_centres.push_back(gt_image.ProjectionCenter());
  }
  errors.gt_ring_coverage = RingCoverage(gt_centres);
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

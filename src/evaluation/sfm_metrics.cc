#include "evaluation/sfm_metrics.h"

#include <tuple>

#include "scene/reconstruction_stats.h"

namespace colmap_gcn {

std::vector<std::string> SfmMetricColumns(
    const std::vector<std::string>& before,
    const std::vector<std::string>& after) {
  std::vector<std::string> columns = before;
  for (const char* column : {"images",
                             "registered",
                             "models",
                             "points",
                             "observations",
                             "track length"}) {
    columns.push_back(column);
  }
  columns.insert(columns.end(), after.begin(), after.end());
  return columns;
}

SfmMetrics EvaluateSparseModels(const std::string& sparse_path,
                                size_t num_images,
                                const Reconstruction* ground_truth,
                                const PoseErrorOptions& pose_options) {
  SfmMetrics metrics;
  metrics.num_images = num_images;
  const std::vector<std::string> models = ListSparseModels(sparse_path);
  metrics.num_models = models.size();
  Reconstruction largest;
  std::tuple<size_t, size_t> best_size(0, 0);
  for (const std::string& model_path : models) {
    Reconstruction reconstruction;
    reconstruction.Read(model_path);
    const std::tuple<size_t, size_t> size(reconstruction.images.size(),
                                          reconstruction.points3D.size());
    if (metrics.largest_model_path.empty() || size > best_size) {
      best_size = size;
      metrics.largest_model_path = model_path;
      largest = std::move(reconstruction);
    }
  }
  if (metrics.largest_model_path.empty()) {
    // No model: every ground-truth image is a failure.
    if (ground_truth != nullptr && !ground_truth->images.empty()) {
      metrics.has_pose_errors = true;
      metrics.pose_errors.num_gt_images = ground_truth->images.size();
      metrics.pose_errors.scene_extent = CameraExtent(*ground_truth);
    }
    return metrics;
  }
  const ReconstructionStatistics stats =
      ComputeReconstructionStatistics(largest);
  metrics.num_registered = stats.num_registered_images;
  metrics.num_points3D = stats.num_points3D;
  metrics.num_observations = stats.num_observations;
  metrics.mean_track_length = stats.mean_track_length;
  metrics.mean_reprojection_error = stats.mean_reprojection_error;
  if (ground_truth != nullptr && !ground_truth->images.empty()) {
    metrics.has_pose_errors = true;
    metrics.pose_errors =
        ComputePoseErrors(largest, *ground_truth, pose_options);
  }
  return metrics;
}

}  // namespace colmap_gcn

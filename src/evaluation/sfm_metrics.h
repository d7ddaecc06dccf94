#pragma once

#include <string>
#include <vector>

#include "evaluation/alignment.h"
#include "scene/reconstruction.h"

namespace colmap_gcn {

// A mapper run in the paper's terms (Tables 4 and 6), on its largest model
// (most registered images; ties: most points, then the lower model index),
// since images registered in several models would otherwise count twice.
struct SfmMetrics {
  size_t num_images = 0;      // images in the database
  size_t num_registered = 0;  // in the largest model
  size_t num_models = 0;
  size_t num_points3D = 0;
  size_t num_observations = 0;
  double mean_track_length = 0;
  double mean_reprojection_error = 0;  // pixels
  std::string largest_model_path;      // "" without a model
  bool has_pose_errors = false;
  PoseErrors pose_errors;  // against ground truth, when available
};

// Reads the models the mapper wrote to sparse_path. ground_truth may be
// null (no pose errors).
SfmMetrics EvaluateSparseModels(const std::string& sparse_path,
                                size_t num_images,
                                const Reconstruction* ground_truth,
                                const PoseErrorOptions& pose_options);

// The mapping table's columns (report.md and gcn_report's page): `before`,
// then num_images through mean_track_length, then `after`.
std::vector<std::string> SfmMetricColumns(
    const std::vector<std::string>& before,
    const std::vector<std::string>& after);

}  // namespace colmap_gcn

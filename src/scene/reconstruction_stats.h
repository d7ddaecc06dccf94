#pragma once

#include <string>
#include <vector>

#include "scene/reconstruction.h"

namespace colmap_gcn {

// The numbers `colmap model_analyzer` reports, computed from a model.
struct ReconstructionStatistics {
  size_t num_registered_images = 0;
  size_t num_points3D = 0;
  size_t num_observations = 0;
  double mean_track_length = 0;
  double mean_reprojection_error = 0;  // over points, in pixels
};

ReconstructionStatistics ComputeReconstructionStatistics(
    const Reconstruction& reconstruction);

// The model folders a mapper run wrote (output_path/0, /1, ...), in order.
std::vector<std::string> ListSparseModels(const std::string& output_path);

}  // namespace colmap_gcn

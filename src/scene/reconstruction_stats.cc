#include "scene/reconstruction_stats.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "util/file.h"

namespace colmap_gcn {

ReconstructionStatistics ComputeReconstructionStatistics(
    const Reconstruction& reconstruction) {
  ReconstructionStatistics stats;
  stats.num_registered_images = reconstruction.images.size();
  stats.num_points3D = reconstruction.points3D.size();
  double error_sum = 0;
  for (const auto& [point3D_id, point3D] : reconstruction.points3D) {
    stats.num_observations += point3D.track.size();
    error_sum += point3D.error;
  }
  if (stats.num_points3D > 0) {
    stats.mean_track_length =
        static_cast<double>(stats.num_observations) / stats.num_points3D;
    stats.mean_reprojection_error = error_sum / stats.num_points3D;
  }
  return stats;
}

std::vector<std::string> ListSparseModels(const std::string& output_path) {
  std::vector<std::pair<long, std::string>> models;
  if (!ExistsDir(output_path)) {
    return {};
  }
  for (const auto& entry : std::filesystem::directory_iterator(output_path)) {
    const std::string name = entry.path().filename().string();
    const bool numeric =
        !name.empty() && std::all_of(name.begin(), name.end(), ::isdigit);
    if (numeric && entry.is_directory()) {
      models.emplace_back(std::stol(name), entry.path().string());
    }
  }
  std::sort(models.begin(), models.end());
  std::vector<std::string> paths;
  for (const auto& model : models) paths.push_back(model.second);
  return paths;
}

}  // namespace colmap_gcn

#include "evaluation/pose_pair_filter.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "controllers/pair_matching.h"
#include "evaluation/json_file.h"
#include "scene/camera_models.h"
#include "scene/database.h"
#include "scene/database_copy.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"

namespace colmap_gcn {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

double RadToDeg(double radians) { return radians * 180.0 / kPi; }

// Optical axis in world coordinates: the camera's +z, R^T (0, 0, 1).
Eigen::Vector3d OpticalAxis(const ModelImage& image) {
  return image.RotationMatrix().row(2).transpose().normalized();
}

}  // namespace

void PosePairFilterOptions::Check() const {
  CHECK_OPTION_RANGE(max_viewpoint_change_deg, 0.0, 180.0);
}

double MaxRayAngleFromAxis(const ModelCamera& camera) {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  const std::string model = CameraModelIdToName(camera.model_id);
  const std::vector<double>& p = camera.params;
  if ((model == "SIMPLE_PINHOLE" || model == "SIMPLE_RADIAL" ||
       model == "RADIAL") &&
      p.size() >= 3) {
    fx = fy = p[0];
    cx = p[1];
    cy = p[2];
  } else if ((model == "PINHOLE" || model == "OPENCV" ||
              model == "FULL_OPENCV") &&
             p.size() >= 4) {
    fx = p[0];
    fy = p[1];
    cx = p[2];
    cy = p[3];
  } else {
    return kPi;  // fisheye or unknown: a field of view up to 180 degrees
  }
  if (fx <= 0 || fy <= 0) return kPi;
  double max_tan = 0;
  for (const double u : {0.0, static_cast<double>(camera.width)}) {
    for (const double v : {0.0, static_cast<double>(camera.height)}) {
      max_tan = std::max(max_tan, std::hypot((u - cx) / fx, (v - cy) / fy));
    }
  }
  return std::atan(max_tan);
}

double MinViewpointChangeDeg(const ModelImage& image1,
                             const ModelCamera& camera1,
                             const ModelImage& image2,
                             const ModelCamera& camera2) {
  const double cosine =
      std::clamp(OpticalAxis(image1).dot(OpticalAxis(image2)), -1.0, 1.0);
  const double bound = std::acos(cosine) - MaxRayAngleFromAxis(camera1) -
                       MaxRayAngleFromAxis(camera2);
  return std::max(0.0, RadToDeg(bound));
}

PosePairSelection SelectPosePairs(const Reconstruction& model,
                                  const PosePairFilterOptions& options) {
  options.Check();
  std::vector<const ModelImage*> images;
  for (const auto& [image_id, image] : model.images) {
    if (model.cameras.count(image.camera_id) == 0) {
      ThrowError("image ", image.name, " has no camera in the model");
    }
    images.push_back(&image);
  }
  std::sort(images.begin(), images.end(), [](const auto* a, const auto* b) {
    return a->name < b->name;
  });
  PosePairSelection selection;
  selection.num_images = images.size();
  for (size_t i = 0; i < images.size(); ++i) {
    const ModelCamera& camera1 = model.cameras.at(images[i]->camera_id);
    for (size_t j = i + 1; j < images.size(); ++j) {
      const ModelCamera& camera2 = model.cameras.at(images[j]->camera_id);
      if (options.Enabled() &&
          MinViewpointChangeDeg(*images[i], camera1, *images[j], camera2) >
              options.max_viewpoint_change_deg) {
        ++selection.num_skipped;
      } else {
        selection.kept.emplace_back(images[i]->name, images[j]->name);
      }
    }
  }
  return selection;
}

LabelMatchingSummary MatchPosePairsForLabels(
    const ColmapRunner& colmap,
    const std::string& base_db,
    const Reconstruction& ground_truth,
    const PosePairFilterOptions& options,
    const PairMatchingOptions& matching,
    const std::string& work_dir) {
  CreateDirIfNotExists(work_dir);
  LabelMatchingSummary summary;
  summary.database_path = JoinPaths(work_dir, "database.db");
  // Copied once: later runs resume matching in the same database.
  if (!ExistsFile(summary.database_path)) {
    const std::string partial = summary.database_path + ".copy";
    CopyDatabase(base_db, partial);
    std::error_code ec;
    fs::rename(partial, summary.database_path, ec);
    if (ec) {
      ThrowError("cannot rename ", partial, ": ", ec.message());
    }
  }

  std::map<std::string, image_t> ids;
  {
    const Database database(base_db);
    for (const DatabaseImage& image : database.ReadAllImages()) {
      ids[image.name] = image.image_id;
    }
  }
  summary.num_images = ids.size();
  summary.num_pairs_total = ids.size() * (ids.size() - 1) / 2;
  Reconstruction posed;
  posed.cameras = ground_truth.cameras;
  for (const auto& [image_id, image] : ground_truth.images) {
    if (ids.count(image.name) > 0) posed.images[image_id] = image;
  }
  summary.num_gt_images = posed.images.size();
  const PosePairSelection selection = SelectPosePairs(posed, options);
  std::vector<ImagePair> pairs;
  for (const auto& [name1, name2] : selection.kept) {
    pairs.emplace_back(ids.at(name1), ids.at(name2));
  }
  summary.num_pairs_matched = pairs.size();

  PairMatchingOptions matching_options = matching;
  matching_options.pairs_path = JoinPaths(work_dir, "pairs.txt");
  const PairMatchingSummary matched =
      MatchImagePairs(colmap, summary.database_path, pairs, matching_options);
  summary.num_pairs_verified = matched.num_verified_pairs;
  if (matched.num_already_matched < matched.num_attempted_pairs) {
    summary.matching_seconds = matched.matching_seconds;
  }

  Json record = Json::object();
  record["max_viewpoint_change_deg"] = options.max_viewpoint_change_deg;
  record["num_images"] = summary.num_images;
  record["num_gt_images"] = summary.num_gt_images;
  record["pairs_total"] = summary.num_pairs_total;
  record["pairs_matched"] = summary.num_pairs_matched;
  record["pairs_skipped"] = selection.num_skipped;
  record["pairs_verified"] = summary.num_pairs_verified;
  record["matching_seconds"] = summary.matching_seconds;
  WriteJsonFile(JoinPaths(work_dir, "label_matching.json"), record);
  return summary;
}

}  // namespace colmap_gcn

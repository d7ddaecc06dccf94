#include "synthetic_evaluation.h"

#include <algorithm>
#include <map>
#include <set>

#include "evaluation/alignment.h"
#include "scene/database.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {

PoseAlignmentResult AlignToGroundTruth(const Reconstruction& ground_truth,
                                       const Reconstruction& model) {
  // The one alignment to ground truth (evaluation/alignment.h), in
  // ground-truth units here.
  const PoseErrors errors =
      ComputePoseErrors(model, ground_truth, PoseErrorOptions());
  PoseAlignmentResult result;
  result.num_gt_images = static_cast<int>(errors.num_gt_images);
  result.num_registered = static_cast<int>(errors.num_evaluated);
  result.scene_size = errors.scene_extent;
  if (errors.num_evaluated < 3) {
    ThrowError("cannot align: only ",
               errors.num_evaluated,
               " model images are in the ground truth");
  }
  if (!errors.aligned) {
    ThrowError("cannot align: the model's camera centres are collinear");
  }
  result.scale = errors.model_to_gt.scale;
  result.median_position_error =
      errors.median_position_error * errors.scene_extent;
  result.max_position_error = *std::max_element(errors.position_errors.begin(),
                                                errors.position_errors.end()) *
                              errors.scene_extent;
  return result;
}

Reconstruction ReadLargestModel(const std::string& sparse_path) {
  Reconstruction best;
  bool found = false;
  for (int k = 0; k < 1000; ++k) {
    const std::string path = JoinPaths(sparse_path, std::to_string(k));
    if (!ExistsDir(path)) {
      break;
    }
    Reconstruction model;
    model.Read(path);
    if (!found || model.images.size() > best.images.size()) {
      best = std::move(model);
      found = true;
    }
  }
  if (!found) {
    ThrowError("no model in ", sparse_path);
  }
  return best;
}

bool TwoViewGeometryRow::IsVerified(int min_num_inliers) const {
  return IsVerifiedTwoViewGeometry(config, num_inliers, min_num_inliers);
}

std::vector<TwoViewGeometryRow> ReadTwoViewGeometries(
    const std::string& database_path) {
  const Database database(database_path);
  std::map<image_t, std::string> names;
  for (const DatabaseImage& image : database.ReadAllImages()) {
    names[image.image_id] = image.name;
  }
  auto name_of = [&names](image_t image_id) {
    const auto it = names.find(image_id);
    return it == names.end() ? std::string() : it->second;
  };
  std::vector<TwoViewGeometryRow> rows;
  for (const TwoViewGeometryInfo& info : database.ReadTwoViewGeometryInfos()) {
    const ImagePair pair = PairIdToImagePair(info.pair_id);
    TwoViewGeometryRow row;
    row.name1 = name_of(pair.first);
    row.name2 = name_of(pair.second);
    row.num_inliers = static_cast<int>(info.num_inliers);
    row.config = info.config;
    rows.push_back(row);
  }
  return rows;
}

OverlapAgreement CompareOverlapWithVerification(
    const PairOverlapTable& table,
    const std::vector<TwoViewGeometryRow>& geometries,
    const std::vector<std::string>& distractor_names,
    double threshold,
    int min_num_inliers,
    double low_threshold) {
  std::set<std::pair<std::string, std::string>> verified;
  for (const TwoViewGeometryRow& row : geometries) {
    if (row.IsVerified(min_num_inliers)) {
      verified.emplace(row.name1, row.name2);
      verified.emplace(row.name2, row.name1);
    }
  }
  const std::set<std::string> distractors(distractor_names.begin(),
                                          distractor_names.end());
  OverlapAgreement agreement;
  for (const PairOverlap& pair : table.Pairs()) {
    const bool is_verified = verified.count({pair.name1, pair.name2}) > 0;
    agreement.num_verified += is_verified;
    if (distractors.count(pair.name1) || distractors.count(pair.name2)) {
      ++agreement.num_distractor_pairs;
      agreement.num_distractor_verified += is_verified;
      continue;
    }
    if (pair.num_shared == 0) {
      ++agreement.num_zero_pairs;
      agreement.num_zero_verified += is_verified;
    } else if (pair.MinOverlap() >= threshold) {
      ++agreement.num_overlap_pairs;
      agreement.num_overlap_verified += is_verified;
    }
    if (pair.num_shared > 0 && pair.MinOverlap() < low_threshold) {
      ++agreement.num_low_pairs;
      agreement.num_low_verified += is_verified;
    }
  }
  return agreement;
}

}  // namespace colmap_gcn

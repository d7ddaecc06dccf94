#include "evaluation/results.h"

namespace colmap_gcn {

Json RetrievalMetricsToJson(const PairSetScore& metrics) {
  Json json = Json::object();
  json["num_pairs"] = metrics.num_pairs;
  json["num_labelled_pairs"] = metrics.num_labelled_pairs;
  json["num_matchable"] = metrics.num_matchable;
  json["num_true_positives"] = metrics.num_true_positives;
  json["num_wrong_pairs"] = metrics.num_wrong_pairs;
  json["precision"] = metrics.precision;
  json["recall"] = metrics.recall;
  json["f_measure"] = metrics.f_measure;
  return json;
}

Json SfmMetricsToJson(const SfmMetrics& metrics) {
  Json json = Json::object();
  json["num_images"] = metrics.num_images;
  json["num_registered"] = metrics.num_registered;
  json["num_models"] = metrics.num_models;
  json["num_points3D"] = metrics.num_points3D;
  json["num_observations"] = metrics.num_observations;
  json["mean_track_length"] = metrics.mean_track_length;
  json["mean_reprojection_error"] = metrics.mean_reprojection_error;
  json["largest_model_path"] = metrics.largest_model_path;
  if (metrics.has_pose_errors) {
    const PoseErrors& pose = metrics.pose_errors;
    Json errors = Json::object();
    errors["num_gt_images"] = pose.num_gt_images;
    errors["num_evaluated"] = pose.num_evaluated;
    errors["aligned"] = pose.aligned;
    errors["scene_extent"] = pose.scene_extent;
    errors["median_rotation_error_deg"] = pose.median_rotation_error_deg;
    errors["median_position_error"] = pose.median_position_error;
    errors["fraction_rotation_ok"] = pose.fraction_rotation_ok;
    errors["fraction_position_ok"] = pose.fraction_position_ok;
    errors["fraction_accurate"] = pose.fraction_accurate;
    errors["ring_coverage"] = pose.ring_coverage;
    errors["gt_ring_coverage"] = pose.gt_ring_coverage;
    Json per_image = Json::array();
    for (size_t i = 0; i < pose.names.size(); ++i) {
      Json image = Json::object();
      image["name"] = pose.names[i];
      image["rotation_error_deg"] = pose.rotation_errors_deg[i];
      image["position_error"] = pose.position_errors[i];
      per_image.push_back(image);
    }
    errors["images"] = per_image;
    json["pose_errors"] = errors;
  }
  return json;
}

Json MethodResultToJson(const MethodResult& result) {
  Json json = Json::object();
  json["method"] = result.method;
  json["status"] = result.status;
  json["message"] = result.message;
  json["k"] = result.k;
  json["tam"] = result.num_attempted;
  json["um"] = result.num_verified;
  json["um_over_tam"] = result.UsefulRatio();
  json["num_verified_wrong"] = result.num_verified_wrong;
  json["lookalike_filter"] = result.lookalike_filter;
  json["lookalike_removed"] = result.num_lookalike_removed;
  json["lookalike_removed_wrong"] = result.num_lookalike_removed_wrong;
  json["lookalike_removed_matchable"] = result.num_lookalike_removed_matchable;
  json["filter_seconds"] = result.filter_seconds;
  json["pairing_seconds"] = result.pairing_seconds;
  json["prepare_seconds"] = result.prepare_seconds;
  json["matching_seconds"] = result.matching_seconds;
  json["mapping_seconds"] = result.mapping_seconds;
  json["session"] = result.session;
  json["retrieval"] = RetrievalMetricsToJson(result.retrieval);
  json["sfm"] = SfmMetricsToJson(result.sfm);
  if (!result.collection.scenes.empty()) {
    json["cross_scene_attempted"] = result.num_cross_scene_attempted;
    json["cross_scene_verified"] = result.num_cross_scene_verified;
    Json collection = Json::object();
    collection["num_models"] = result.collection.num_models;
    collection["num_mixed_models"] = result.collection.num_mixed_models;
    Json scenes = Json::object();
    for (const auto& [scene, entry] : result.collection.scenes) {
      scenes[scene] = {{"num_images", entry.num_images},
                       {"num_registered", entry.num_registered},
                       {"num_models", entry.num_models}};
    }
    collection["scenes"] = scenes;
    json["collection"] = collection;
  }
  return json;
}

Json SceneResultToJson(const SceneResult& result) {
  Json json = Json::object();
  json["name"] = result.name;
  json["kind"] = result.kind;
  json["label_source"] = result.label_source;
  json["status"] = result.status;
  json["message"] = result.message;
  json["num_images"] = result.num_images;
  json["num_labelled_images"] = result.num_labelled_images;
  json["num_matchable_pairs"] = result.num_matchable_pairs;
  json["has_gt_cameras"] = result.has_gt_cameras;
  json["extraction_seconds"] = result.extraction_seconds;
  if (result.is_collection) {
    json["is_collection"] = true;
    Json alone = Json::object();
    for (const auto& [scene, registered] : result.registered_alone) {
      alone[scene] = registered;
    }
    json["registered_alone"] = alone;
  }
  Json methods = Json::array();
  for (const MethodResult& method : result.methods) {
    methods.push_back(MethodResultToJson(method));
  }
  json["methods"] = methods;
  Json figures = Json::array();
  for (const std::string& figure : result.figures) figures.push_back(figure);
  json["figures"] = figures;
  return json;
}

Json BenchmarkResultsToJson(const BenchmarkResults& results) {
  Json json = Json::object();
  json["command"] = results.command;
  json["tau_mo"] = results.label_options.min_overlap;
  json["tau_ct"] = results.label_options.min_common_track_ratio;
  json["max_rotation_error_deg"] = results.pose_options.max_rotation_error_deg;
  json["max_position_error"] = results.pose_options.max_position_error;
  Json methods = Json::array();
  for (const std::string& method : results.methods) methods.push_back(method);
  json["methods"] = methods;
  Json scenes = Json::array();
  for (const SceneResult& scene : results.scenes) {
    scenes.push_back(SceneResultToJson(scene));
  }
  json["scenes"] = scenes;
  return json;
}

}  // namespace colmap_gcn

#include "evaluation/results.h"

namespace colmap_gcn {

JsonValue RetrievalMetricsToJson(const RetrievalMetrics& metrics) {
  JsonValue json = JsonValue::Object();
  json["num_pairs"] = JsonValue(static_cast<uint64_t>(metrics.num_pairs));
  json["num_labelled_pairs"] =
      JsonValue(static_cast<uint64_t>(metrics.num_labelled_pairs));
  json["num_matchable"] =
      JsonValue(static_cast<uint64_t>(metrics.num_matchable));
  json["num_true_positives"] =
      JsonValue(static_cast<uint64_t>(metrics.num_true_positives));
  json["num_wrong_pairs"] =
      JsonValue(static_cast<uint64_t>(metrics.num_wrong_pairs));
  json["precision"] = metrics.precision;
  json["recall"] = metrics.recall;
  json["f_measure"] = metrics.f_measure;
  return json;
}

JsonValue SfmMetricsToJson(const SfmMetrics& metrics) {
  JsonValue json = JsonValue::Object();
  json["num_images"] = JsonValue(static_cast<uint64_t>(metrics.num_images));
  json["num_registered"] =
      JsonValue(static_cast<uint64_t>(metrics.num_registered));
  json["num_models"] = JsonValue(static_cast<uint64_t>(metrics.num_models));
  json["num_points3D"] = JsonValue(static_cast<uint64_t>(metrics.num_points3D));
  json["num_observations"] =
      JsonValue(static_cast<uint64_t>(metrics.num_observations));
  json["mean_track_length"] = metrics.mean_track_length;
  json["mean_reprojection_error"] = metrics.mean_reprojection_error;
  json["largest_model_path"] = metrics.largest_model_path;
  if (metrics.has_pose_errors) {
    const PoseErrors& pose = metrics.pose_errors;
    JsonValue errors = JsonValue::Object();
    errors["num_gt_images"] =
        JsonValue(static_cast<uint64_t>(pose.num_gt_images));
    errors["num_evaluated"] =
        JsonValue(static_cast<uint64_t>(pose.num_evaluated));
    errors["aligned"] = pose.aligned;
    errors["scene_extent"] = pose.scene_extent;
    errors["median_rotation_error_deg"] = pose.median_rotation_error_deg;
    errors["median_position_error"] = pose.median_position_error;
    errors["fraction_rotation_ok"] = pose.fraction_rotation_ok;
    errors["fraction_position_ok"] = pose.fraction_position_ok;
    errors["fraction_accurate"] = pose.fraction_accurate;
    JsonValue per_image = JsonValue::Array();
    for (size_t i = 0; i < pose.names.size(); ++i) {
      JsonValue image = JsonValue::Object();
      image["name"] = pose.names[i];
      image["rotation_error_deg"] = pose.rotation_errors_deg[i];
      image["position_error"] = pose.position_errors[i];
      per_image.Append(image);
    }
    errors["images"] = per_image;
    json["pose_errors"] = errors;
  }
  return json;
}

JsonValue MethodResultToJson(const MethodResult& result) {
  JsonValue json = JsonValue::Object();
  json["method"] = result.method;
  json["status"] = result.status;
  json["message"] = result.message;
  json["k"] = result.k;
  json["tam"] = JsonValue(static_cast<uint64_t>(result.num_attempted));
  json["um"] = JsonValue(static_cast<uint64_t>(result.num_verified));
  json["um_over_tam"] = result.UsefulRatio();
  json["num_verified_wrong"] =
      JsonValue(static_cast<uint64_t>(result.num_verified_wrong));
  json["pairing_seconds"] = result.pairing_seconds;
  json["matching_seconds"] = result.matching_seconds;
  json["mapping_seconds"] = result.mapping_seconds;
  json["session"] = result.session;
  json["retrieval"] = RetrievalMetricsToJson(result.retrieval);
  json["sfm"] = SfmMetricsToJson(result.sfm);
  return json;
}

JsonValue SceneResultToJson(const SceneResult& result) {
  JsonValue json = JsonValue::Object();
  json["name"] = result.name;
  json["kind"] = result.kind;
  json["label_source"] = result.label_source;
  json["status"] = result.status;
  json["message"] = result.message;
  json["num_images"] = JsonValue(static_cast<uint64_t>(result.num_images));
  json["num_labelled_images"] =
      JsonValue(static_cast<uint64_t>(result.num_labelled_images));
  json["num_matchable_pairs"] =
      JsonValue(static_cast<uint64_t>(result.num_matchable_pairs));
  json["has_gt_cameras"] = result.has_gt_cameras;
  json["extraction_seconds"] = result.extraction_seconds;
  JsonValue methods = JsonValue::Array();
  for (const MethodResult& method : result.methods) {
    methods.Append(MethodResultToJson(method));
  }
  json["methods"] = methods;
  JsonValue figures = JsonValue::Array();
  for (const std::string& figure : result.figures) figures.Append(figure);
  json["figures"] = figures;
  return json;
}

JsonValue BenchmarkResultsToJson(const BenchmarkResults& results) {
  JsonValue json = JsonValue::Object();
  json["command"] = results.command;
  json["tau_mo"] = results.label_options.min_overlap;
  json["tau_ct"] = results.label_options.min_common_track_ratio;
  json["max_rotation_error_deg"] = results.pose_options.max_rotation_error_deg;
  json["max_position_error"] = results.pose_options.max_position_error;
  JsonValue methods = JsonValue::Array();
  for (const std::string& method : results.methods) methods.Append(method);
  json["methods"] = methods;
  JsonValue scenes = JsonValue::Array();
  for (const SceneResult& scene : results.scenes) {
    scenes.Append(SceneResultToJson(scene));
  }
  json["scenes"] = scenes;
  return json;
}

}  // namespace colmap_gcn

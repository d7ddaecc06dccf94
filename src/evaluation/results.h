#pragma once

#include <map>
#include <string>
#include <vector>

#include "evaluation/collection.h"
#include "evaluation/json_file.h"
#include "evaluation/labels.h"
#include "evaluation/metrics.h"
#include "evaluation/sfm_metrics.h"

namespace colmap_gcn {

// One method on one scene.
struct MethodResult {
  std::string method;             // spec, e.g. "knn:25"
  std::string status = "ok";      // ok | unavailable | failed
  std::string message;            // why, when not ok
  int k = 0;                      // effective retrieval depth (0: n/a)
  size_t num_attempted = 0;       // TAM
  size_t num_verified = 0;        // UM
  size_t num_verified_wrong = 0;  // verified pairs that share nothing
  // The look-alike filter (docs/lookalike.md): whether it ran, the verified
  // pairs it hid from the mapper, of those the labels' wrong (sharing
  // nothing) and matchable ones, and its time.
  bool lookalike_filter = false;
  size_t num_lookalike_removed = 0;
  size_t num_lookalike_removed_wrong = 0;
  size_t num_lookalike_removed_matchable = 0;
  double filter_seconds = 0;
  double pairing_seconds = 0;  // choosing the pairs
  // Made once before pairing and not counted in pairing_seconds (vocab_tree:
  // building the tree a user would download).
  double prepare_seconds = 0;
  double matching_seconds = 0;  // COLMAP matching + verification
  double mapping_seconds = 0;
  std::string session;  // the benchmark run that matched
  std::string same_as;  // the method whose run this row repeats, or ""
  PairSetScore retrieval;
  SfmMetrics sfm;
  // Merged collections only (collection.h): pairs across scenes, attempted
  // and verified, and each scene's registration.
  size_t num_cross_scene_attempted = 0;
  size_t num_cross_scene_verified = 0;
  CollectionRegistration collection;

  bool Ok() const { return status == "ok"; }
  double UsefulRatio() const {
    return num_attempted == 0
               ? 0.0
               : static_cast<double>(num_verified) / num_attempted;
  }
};

struct SceneResult {
  std::string name;
  std::string kind;  // images | 1dsfm | synthetic
  std::string label_source;
  std::string status = "ok";
  std::string message;
  size_t num_images = 0;
  size_t num_labelled_images = 0;
  size_t num_matchable_pairs = 0;
  bool has_gt_cameras = false;
  double extraction_seconds = 0;
  std::vector<std::string> image_names;  // sorted, for figures
  // A merged collection ("<scene>__<name>" images, collection.h), and its
  // scenes' registered images when benchmarked alone with exhaustive
  // matching (empty without --Benchmark.alone_results_path).
  bool is_collection = false;
  std::map<std::string, size_t> registered_alone;
  std::vector<MethodResult> methods;
  std::vector<std::string> figures;  // relative to the output folder
};

struct BenchmarkResults {
  std::vector<SceneResult> scenes;
  std::vector<std::string> methods;  // specs, in --methods order
  std::string command;               // the command line, for the report
  PairLabelOptions label_options;
  PoseErrorOptions pose_options;
};

Json RetrievalMetricsToJson(const PairSetScore& metrics);
Json SfmMetricsToJson(const SfmMetrics& metrics);
Json MethodResultToJson(const MethodResult& result);
Json SceneResultToJson(const SceneResult& result);
Json BenchmarkResultsToJson(const BenchmarkResults& results);

}  // namespace colmap_gcn

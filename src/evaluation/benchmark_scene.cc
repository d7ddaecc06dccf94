#include "evaluation/benchmark_runner.h"

#include <unistd.h>

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "controllers/colmap_runner.h"
#include "controllers/feature_extraction.h"
#include "controllers/gcn_matching.h"
#include "controllers/incremental_mapping.h"
#include "controllers/pair_matching.h"
#include "disambiguation/pair_filter.h"
#include "evaluation/collection.h"
#include "evaluation/common_tracks.h"
#include "evaluation/dataset.h"
#include "evaluation/figures.h"
#include "evaluation/method.h"
#include "evaluation/pair_labels.h"
#include "evaluation/pose_pair_filter.h"
#include "evaluation/report.h"
#include "pairing/pair_generator_registry.h"
#include "pairing/pairs_io.h"
#include "scene/database_copy.h"
#include "scene/database_validation.h"
#include "scene/reconstruction_stats.h"
#include "synthetic/pair_overlap.h"
#include "util/error.h"
#include "util/file.h"
#include "util/interrupt.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace internal {

void BenchmarkRunner::Extract(SceneContext* scene, SceneResult* result) {
  const std::string record_path = JoinPaths(scene->dir, "extraction.json");
  scene->base_db = JoinPaths(scene->dir, "base.db");
  if (ExistsFile(record_path) && ExistsFile(scene->base_db)) {
    result->extraction_seconds =
        ReadJsonFile(record_path).value("seconds", 0.0);
    Progress(scene->dataset.name, "features cached in " + scene->base_db);
    return;
  }
  Progress(scene->dataset.name,
           "feature_extractor on " +
               std::to_string(scene->dataset.image_names.size()) + " images");
  // COLMAP extracts into a scratch file that replaces base.db only when
  // complete, so an interrupted extraction is redone rather than trusted.
  FeatureExtractionOptions extraction_options;
  extraction_options.image_path = scene->dataset.image_path;
  extraction_options.image_list_path = scene->dataset.image_list_path;
  extraction_options.single_camera = options_.single_camera < 0
                                         ? scene->dataset.single_camera
                                         : options_.single_camera != 0;
  extraction_options.replace_database = true;
  // A scene with too few images shows as such in every method's row.
  extraction_options.min_num_images = 0;
  extraction_options.colmap_args = options_.extraction_args;
  result->extraction_seconds =
      ExtractFeatures(Colmap(*scene), scene->base_db, extraction_options)
          .seconds;
  Json record = Json::object();
  record["seconds"] = result->extraction_seconds;
  record["session"] = session_;
  WriteJsonFile(record_path, record);
  Progress(
      scene->dataset.name,
      "features extracted in " + FormatSeconds(result->extraction_seconds));
}

void BenchmarkRunner::LoadGroundTruth(SceneContext* scene) {
  if (scene->dataset.gt_path.empty()) return;
  Reconstruction gt;
  gt.Read(scene->dataset.gt_path);
  std::set<std::string> names(scene->image_names.begin(),
                              scene->image_names.end());
  for (const auto& [image_id, image] : gt.images) {
    if (names.count(image.name) == 0) continue;
    scene->gt.images[image_id] = image;
    scene->gt.images[image_id].points2D.clear();
    scene->gt.images[image_id].point3D_ids.clear();
    scene->gt.cameras[image.camera_id] = gt.cameras.at(image.camera_id);
  }
  scene->has_gt = scene->gt.images.size() >= 3;
}

namespace {

// Labels of a rendered scene from its exact overlaps, for the images in the
// database.
PairLabels SyntheticOverlapLabels(const std::string& overlap_path,
                                  const std::set<std::string>& db_names) {
  const PairOverlapTable table = ReadPairOverlapTable(overlap_path);
  std::set<std::string> names;
  for (const PairOverlap& pair : table.Pairs()) {
    if (db_names.count(pair.name1)) names.insert(pair.name1);
    if (db_names.count(pair.name2)) names.insert(pair.name2);
  }
  PairLabels labels({names.begin(), names.end()},
                    /*has_overlap=*/true,
                    /*has_common_track_ratio=*/false);
  for (const PairOverlap& pair : table.Pairs()) {
    // MO = shared / min(visible1, visible2), the same normalisation as the
    // common-track ratio, so both thresholds read alike.
    if (pair.num_shared > 0 && labels.IsLabelled(pair.name1, pair.name2)) {
      labels.SetOverlap(pair.name1, pair.name2, pair.MaxOverlap());
    }
  }
  return labels;
}

}  // namespace

void BenchmarkRunner::BuildLabels(SceneContext* scene, SceneResult* result) {
  const std::string labels_dir = JoinPaths(scene->dir, "labels");
  CreateDirIfNotExists(labels_dir);
  const std::string labels_path = JoinPaths(labels_dir, "labels.csv");
  const std::string& name = scene->dataset.name;
  if (ExistsFile(labels_path)) {
    scene->labels = PairLabels::Read(labels_path);
    Progress(name, "labels cached in " + labels_path);
  } else {
    const std::set<std::string> db_names(scene->image_names.begin(),
                                         scene->image_names.end());
    switch (scene->dataset.label_source) {
      case LabelSource::kSyntheticOverlap:
        scene->labels =
            SyntheticOverlapLabels(scene->dataset.overlap_path, db_names);
        break;
      case LabelSource::kGroundTruthTriangulation: {
        std::string matched_db;
        if (options_.label_pair_filter.Enabled()) {
          Progress(name, "matching the pairs the pose filter keeps");
          const LabelMatchingSummary summary =
              MatchPosePairsForLabels(Colmap(*scene),
                                      scene->base_db,
                                      scene->gt,
                                      options_.label_pair_filter,
                                      options_.MatchingOptions(),
                                      JoinPaths(labels_dir, "matching"));
          Progress(name,
                   "matched " + std::to_string(summary.num_pairs_matched) +
                       " of " + std::to_string(summary.num_pairs_total) +
                       " pairs for the labels");
          matched_db = summary.database_path;
        } else {
          const BenchmarkMethod exhaustive = ParseBenchmarkMethod("exhaustive");
          MatchMethod(*scene, exhaustive);
          matched_db = JoinPaths(MethodDir(*scene, exhaustive), "database.db");
          // Labels see every verified pair, the look-alike filter's too.
          if (!TwoViewGeometryStore(matched_db).ReadHiddenPairs().empty()) {
            const std::string copy = JoinPaths(labels_dir, "unfiltered.db");
            CopyDatabase(matched_db, copy);
            RestoreLookalikePairs(copy);
            matched_db = copy;
          }
        }
        Progress(name,
                 "triangulating the matches on the GT cameras "
                 "(point_triangulator)");
        // The retrieval module's GT-camera labels (the same labels its
        // retrieval-quality tools use).
        scene->labels = ComputeGroundTruthCameraLabels(
            Colmap(*scene),
            matched_db,
            scene->dataset.gt_path,
            JoinPaths(labels_dir, "gt_triangulation"));
        break;
      }
      case LabelSource::kReferenceModel: {
        Reconstruction reference;
        reference.Read(scene->dataset.reference_path);
        scene->labels = LabelsFromReconstruction(
            reference, scene->image_names, "reference model");
        break;
      }
      case LabelSource::kExhaustiveReference: {
        const BenchmarkMethod exhaustive = ParseBenchmarkMethod("exhaustive");
        MatchMethod(*scene, exhaustive);
        const Json run = MapMethod(*scene, exhaustive);
        const SfmMetrics sfm = EvaluateSparseModels(
            JoinPaths(MethodDir(*scene, exhaustive), "sparse"),
            scene->images.size(),
            nullptr,
            options_.pose);
        if (sfm.largest_model_path.empty()) {
          ThrowError("no exhaustive reference model for the labels of ", name);
        }
        Reconstruction reference;
        reference.Read(sfm.largest_model_path);
        scene->labels = LabelsFromReconstruction(
            reference, scene->image_names, "exhaustive reference model");
        break;
      }
    }
    scene->labels.source = LabelSourceName(scene->dataset.label_source);
    scene->labels.Write(labels_path);
  }
  // The oracle's pairs depend on the thresholds, so they are rewritten on
  // every run (the oracle's cache records the thresholds it used).
  std::ostringstream pairs;
  for (const auto& [name1, name2] :
       scene->labels.MatchablePairs(options_.labels)) {
    pairs << name1 << " " << name2 << "\n";
  }
  scene->oracle_pairs_path = JoinPaths(labels_dir, "oracle_pairs.txt");
  WriteFileAtomically(scene->oracle_pairs_path, pairs.str());
  result->label_source = scene->labels.source;
  result->num_labelled_images = scene->labels.ImageNames().size();
  result->num_matchable_pairs =
      scene->labels.MatchablePairs(options_.labels).size();
  Progress(name,
           std::to_string(result->num_matchable_pairs) +
               " matchable pairs among " +
               std::to_string(result->num_labelled_images) +
               " labelled images (" + scene->labels.source + ")");
}

}  // namespace internal
}  // namespace colmap_gcn

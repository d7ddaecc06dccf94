#include "evaluation/benchmark.h"

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
#include "controllers/pair_generator_registry.h"
#include "controllers/pair_matching.h"
#include "evaluation/collection.h"
#include "evaluation/common_tracks.h"
#include "evaluation/dataset.h"
#include "evaluation/figures.h"
#include "evaluation/method.h"
#include "evaluation/pair_labels.h"
#include "evaluation/pose_pair_filter.h"
#include "evaluation/report.h"
#include "feature/pairs_io.h"
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
namespace {

namespace fs = std::filesystem;

void Progress(const std::string& scene, const std::string& message) {
  LOG(INFO) << scene << ": " << message;
}

std::string FormatSeconds(double seconds) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.1f s", seconds);
  return buffer;
}

// Identifies one benchmark invocation; stored with every matching result so
// the report can tell when cached times come from different runs.
std::string NewSessionId() {
  const std::time_t now = std::time(nullptr);
  char buffer[64];
  std::strftime(
      buffer, sizeof(buffer), "%Y-%m-%dT%H:%M:%S", std::localtime(&now));
  return std::string(buffer) + "-" + std::to_string(getpid());
}

void RemovePath(const std::string& path) {
  std::error_code ec;
  fs::remove_all(path, ec);
}

// A fresh database for one method: the scene's extracted base, with no
// working copy of an earlier interrupted run beside it.
void CopyBaseDatabase(const std::string& from, const std::string& to) {
  for (const char* suffix :
       {".gcn-partial", ".gcn-partial.source", ".gcn-partial.pairs.txt"}) {
    RemoveDatabaseFiles(to + suffix);
  }
  CopyDatabase(from, to);
}

// Identifies a pair set regardless of order and orientation.
std::string PairSetHash(const std::vector<ImagePair>& pairs) {
  std::vector<image_pair_t> ids;
  for (const ImagePair& pair : pairs) {
    if (pair.first != pair.second) {
      ids.push_back(ImagePairToPairId(pair.first, pair.second));
    }
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  // FNV-1a over the sorted ids: deterministic across runs and builds.
  uint64_t hash = 1469598103934665603ull;
  for (const image_pair_t id : ids) {
    for (int byte = 0; byte < 8; ++byte) {
      hash ^= (id >> (8 * byte)) & 0xff;
      hash *= 1099511628211ull;
    }
  }
  return std::to_string(ids.size()) + "-" + std::to_string(hash);
}

// Everything the methods of one scene share.
struct SceneContext {
  Dataset dataset;
  std::string dir;
  std::string base_db;
  std::vector<DatabaseImage> images;
  std::map<image_t, std::string> names_by_id;
  std::vector<std::string> image_names;  // sorted
  bool has_gt = false;
  Reconstruction gt;  // restricted to the database's images
  PairLabels labels;
  std::string oracle_pairs_path;
};

class BenchmarkRunner {
 public:
  explicit BenchmarkRunner(const BenchmarkOptions& options)
      : options_(options),
        session_(NewSessionId()),
        methods_(ParseBenchmarkMethods(options.methods)) {}

  BenchmarkResults Run();

 private:
  SceneResult RunScene(const DatasetSpec& spec);
  void Extract(SceneContext* scene, SceneResult* result);
  void LoadGroundTruth(SceneContext* scene);
  void BuildLabels(SceneContext* scene, SceneResult* result);
  std::string MethodDir(const SceneContext& scene,
                        const BenchmarkMethod& method) const {
    return JoinPaths(scene.dir, method.DirName());
  }
  // Runs (or reads from the cache) the matching and mapping of a method;
  // returns its run record. Matching and mapping are cached separately so
  // the exhaustive matches can serve the labels first.
  Json MatchMethod(const SceneContext& scene, const BenchmarkMethod& method);
  Json MapMethod(const SceneContext& scene, const BenchmarkMethod& method);
  MethodResult EvaluateMethod(const SceneContext& scene,
                              const BenchmarkMethod& method,
                              const Json& run,
                              SceneResult* scene_result);
  std::unique_ptr<PairGenerator> CreateGenerator(
      const SceneContext& scene, const BenchmarkMethod& method) const;
  const ColmapRunner& Colmap(const SceneContext& scene);

  const BenchmarkOptions& options_;
  const std::string session_;
  const std::vector<BenchmarkMethod> methods_;
  // Pair-set hash -> spec of the first listed method of the current scene
  // that matched exactly these pairs.
  std::map<std::string, std::string> pair_set_owners_;
  std::unique_ptr<ColmapRunner> colmap_;
  std::string colmap_log_;
};

const ColmapRunner& BenchmarkRunner::Colmap(const SceneContext& scene) {
  const std::string log_path = JoinPaths(scene.dir, "colmap.log");
  if (!colmap_ || colmap_log_ != log_path) {
    ColmapRunnerOptions runner_options;
    runner_options.colmap_exe = options_.colmap_exe;
    runner_options.log_path = log_path;
    runner_options.verbose = options_.verbose;
    runner_options.show_progress = options_.verbose;
    colmap_ = std::make_unique<ColmapRunner>(runner_options);
    colmap_log_ = log_path;
  }
  return *colmap_;
}

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
      case LabelSource::kSyntheticOverlap: {
        const PairOverlapTable table =
            ReadPairOverlapTable(scene->dataset.overlap_path);
        std::set<std::string> names;
        for (const PairOverlap& pair : table.Pairs()) {
          if (db_names.count(pair.name1)) names.insert(pair.name1);
          if (db_names.count(pair.name2)) names.insert(pair.name2);
        }
        scene->labels = PairLabels({names.begin(), names.end()},
                                   /*has_overlap=*/true,
                                   /*has_common_track_ratio=*/false);
        for (const PairOverlap& pair : table.Pairs()) {
          // MO = shared / min(visible1, visible2), the same normalisation
          // as the common-track ratio, so both thresholds read alike.
          if (pair.num_shared > 0 &&
              scene->labels.IsLabelled(pair.name1, pair.name2)) {
            scene->labels.SetOverlap(pair.name1, pair.name2, pair.MaxOverlap());
          }
        }
        break;
      }
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

std::unique_ptr<PairGenerator> BenchmarkRunner::CreateGenerator(
    const SceneContext& scene, const BenchmarkMethod& method) const {
  const PairGeneratorRegistry& registry = PairGenerators();
  const Database database(scene.base_db);
  PairGeneratorContext context(database);
  context.colmap_log_path = options_.gcn_matching.matching.colmap_log_path;
  context.verbose = options_.gcn_matching.matching.verbose;
  if (method.IsOracle()) {
    PairGeneratorOptions oracle = registry.DefaultOptions();
    oracle.Get<ImagePairsMatchingOptions>("imported").match_list_path =
        scene.oracle_pairs_path;
    return registry.Create("imported", oracle, context);
  }
  PairGeneratorOptions options = options_.gcn_matching.generators;
  if (int* depth = registry.Depth(method.pairing, &options)) {
    *depth = method.EffectiveK(scene.images.size());
  }
  return registry.Create(method.pairing, options, context);
}

Json BenchmarkRunner::MatchMethod(const SceneContext& scene,
                                  const BenchmarkMethod& method) {
  const std::string dir = MethodDir(scene, method);
  const std::string run_path = JoinPaths(dir, "run.json");
  const std::string& name = scene.dataset.name;
  if (ExistsFile(run_path)) {
    Json run = ReadJsonFile(run_path);
    const bool thresholds_changed =
        method.IsOracle() &&
        (run.value("tau_mo", -1.0) != options_.labels.min_overlap ||
         run.value("tau_ct", -1.0) != options_.labels.min_common_track_ratio);
    // A "same pairs as" record is only valid while its owner is one of
    // this scene's runs.
    const auto owner =
        pair_set_owners_.find(run.value("pairs_hash", std::string()));
    const bool stale_duplicate =
        run.contains("same_as") &&
        (owner == pair_set_owners_.end() ||
         owner->second != run.at("same_as").get<std::string>() ||
         owner->second == method.spec);
    if (!thresholds_changed && !stale_duplicate) {
      Progress(name, method.spec + ": matching cached");
      return run;
    }
    Progress(name,
             method.spec +
                 ": cached run outdated (thresholds or pair set), rerunning");
  }
  RemovePath(dir);
  CreateDirIfNotExists(dir);

  Json run = Json::object();
  run["method"] = method.spec;
  run["k"] = method.EffectiveK(scene.images.size());
  run["session"] = session_;
  if (method.IsOracle()) {
    run["tau_mo"] = options_.labels.min_overlap;
    run["tau_ct"] = options_.labels.min_common_track_ratio;
  }
  std::vector<ImagePair> pairs;
  std::unique_ptr<PairGenerator> generator;
  const Timer pairing_timer;
  try {
    generator = CreateGenerator(scene, method);
    // Generators that use verification choose their pairs while matching.
    if (!generator->UsesVerification()) pairs = generator->AllPairs();
  } catch (const Error& error) {
    // Not cached: the method may exist in the next build.
    RemovePath(dir);
    Progress(name, method.spec + ": unavailable (" + error.what() + ")");
    run["status"] = "unavailable";
    run["message"] = error.what();
    run["session"] = "";  // nothing was run
    return run;
  }
  run["pairing_seconds"] = pairing_timer.ElapsedSeconds();
  const bool in_the_loop = generator->UsesVerification();
  const std::string pairs_hash = in_the_loop ? "" : PairSetHash(pairs);
  if (!in_the_loop) run["pairs_hash"] = pairs_hash;
  const auto same = pair_set_owners_.find(pairs_hash);
  if (!in_the_loop && same != pair_set_owners_.end() &&
      same->second != method.spec) {
    // Identical pairs (e.g. knn with k >= N - 1 and exhaustive): matching
    // and mapping them again would only cost time.
    run["status"] = "ok";
    run["same_as"] = same->second;
    Progress(name, method.spec + ": same pairs as " + same->second);
    WriteJsonFile(run_path, run);
    return run;
  }

  const std::string db = JoinPaths(dir, "database.db");
  CopyBaseDatabase(scene.base_db, db);
  PairMatchingOptions matching_options = options_.MatchingOptions();
  matching_options.pairs_path = JoinPaths(dir, "pairs.txt");
  Progress(name,
           method.spec + ": matching " +
               (in_the_loop ? std::string("in rounds")
                            : std::to_string(pairs.size()) + " pairs"));
  try {
    const PairMatchingSummary summary =
        in_the_loop
            ? MatchPairGenerator(
                  Colmap(scene), db, generator.get(), matching_options, &pairs)
            : MatchImagePairs(Colmap(scene), db, pairs, matching_options);
    if (in_the_loop) {
      run["pairs_hash"] = PairSetHash(pairs);
      run["rounds"] = summary.num_rounds;
      run["pairing_seconds"] =
          run["pairing_seconds"].get<double>() + summary.generator_seconds;
    }
    run["status"] = "ok";
    run["tam"] = summary.num_attempted_pairs;
    run["um"] = summary.num_verified_pairs;
    run["matching_seconds"] = summary.matching_seconds;
    Progress(name,
             method.spec + ": TAM " +
                 std::to_string(summary.num_attempted_pairs) + ", UM " +
                 std::to_string(summary.num_verified_pairs) + " in " +
                 FormatSeconds(summary.matching_seconds));
  } catch (const Error& error) {
    // An interruption is no result of the method: nothing is cached, the
    // run stops, and the next one matches this method again.
    if (PendingInterrupt() != 0) throw;
    run["status"] = "failed";
    run["message"] = std::string("matching: ") + error.what();
    Progress(name, method.spec + ": matching failed: " + error.what());
  }
  WriteJsonFile(run_path, run);
  return run;
}

Json BenchmarkRunner::MapMethod(const SceneContext& scene,
                                const BenchmarkMethod& method) {
  const std::string dir = MethodDir(scene, method);
  const std::string run_path = JoinPaths(dir, "run.json");
  Json run = ReadJsonFile(run_path);
  if (run.value("status", std::string()) != "ok" ||
      run.contains("mapping_seconds")) {
    return run;
  }
  const std::string sparse = JoinPaths(dir, "sparse");
  IncrementalMappingOptions mapping_options;
  mapping_options.image_path = scene.dataset.image_path;
  mapping_options.num_threads = options_.mapper_num_threads;
  // COLMAP discards models under 10 images; the benchmark's small scenes
  // would lose every partial model, which the tables should show.
  mapping_options.min_model_size = options_.mapper_min_model_size;
  mapping_options.replace_models = true;
  mapping_options.colmap_args = options_.mapper_args;
  Progress(scene.dataset.name, method.spec + ": mapper");
  const Timer timer;
  try {
    RunIncrementalMapping(
        Colmap(scene), JoinPaths(dir, "database.db"), sparse, mapping_options);
  } catch (const Error& error) {
    if (PendingInterrupt() != 0) throw;  // mapped again by the next run
    // COLMAP 3.8's mapper exits 1 when it builds no model: for the tables
    // that is a result (0 registered, the paper's "Fail"), not an error.
    run["message"] = "mapper produced no model";
    if (!ListSparseModels(sparse).empty()) {
      run["status"] = "failed";
      run["message"] = std::string("mapper: ") + error.what();
    }
    Progress(scene.dataset.name,
             method.spec + ": " + run.value("message", std::string()));
  }
  run["mapping_seconds"] = timer.ElapsedSeconds();
  WriteJsonFile(run_path, run);
  return run;
}

MethodResult BenchmarkRunner::EvaluateMethod(const SceneContext& scene,
                                             const BenchmarkMethod& method,
                                             const Json& run,
                                             SceneResult* scene_result) {
  MethodResult result;
  result.method = method.spec;
  result.status = run.value("status", std::string("failed"));
  result.message = run.value("message", std::string());
  result.k = static_cast<int>(run.value("k", int64_t{0}));
  result.session = run.value("session", std::string());
  result.pairing_seconds = run.value("pairing_seconds", 0.0);
  result.matching_seconds = run.value("matching_seconds", 0.0);
  result.mapping_seconds = run.value("mapping_seconds", 0.0);
  result.num_attempted = run.value("tam", size_t{0});
  result.num_verified = run.value("um", size_t{0});
  const std::string dir = MethodDir(scene, method);
  const std::string pairs_path = JoinPaths(dir, "pairs.txt");
  if (!ExistsFile(pairs_path)) return result;

  const std::vector<ImageNamePair> attempted = ReadPairsFile(pairs_path);
  result.retrieval =
      ComputeRetrievalMetrics(attempted, scene.labels, options_.labels);
  std::vector<ImageNamePair> verified;
  {
    const Database database(JoinPaths(dir, "database.db"));
    const int min_num_inliers = options_.gcn_matching.matching.min_num_inliers;
    for (const TwoViewGeometryInfo& info :
         database.ReadTwoViewGeometryInfos()) {
      if (!IsVerifiedTwoViewGeometry(
              info.config, info.num_inliers, min_num_inliers)) {
        continue;
      }
      const ImagePair pair = PairIdToImagePair(info.pair_id);
      const auto a = scene.names_by_id.find(pair.first);
      const auto b = scene.names_by_id.find(pair.second);
      if (a == scene.names_by_id.end() || b == scene.names_by_id.end()) {
        continue;
      }
      verified.emplace_back(a->second, b->second);
      if (scene.labels.SharesNothing(a->second, b->second)) {
        ++result.num_verified_wrong;
      }
    }
  }
  result.sfm = EvaluateSparseModels(JoinPaths(dir, "sparse"),
                                    scene.images.size(),
                                    scene.has_gt ? &scene.gt : nullptr,
                                    options_.pose);
  if (scene_result->is_collection) {
    result.num_cross_scene_attempted = CountCrossScenePairs(attempted);
    result.num_cross_scene_verified = CountCrossScenePairs(verified);
    result.collection =
        ReadCollectionRegistration(scene.image_names, JoinPaths(dir, "sparse"));
  }

  const std::string figure_dir =
      JoinPaths(JoinPaths(options_.output_path, "figures"), scene.dataset.name);
  CreateDirIfNotExists(figure_dir);
  const std::string figure = method.DirName() + "_view_graph.png";
  WriteViewGraphImage(JoinPaths(figure_dir, figure),
                      scene.image_names,
                      attempted,
                      verified,
                      scene.labels,
                      options_.labels);
  scene_result->figures.push_back("figures/" + scene.dataset.name + "/" +
                                  figure);
  WriteJsonFile(JoinPaths(dir, "result.json"), MethodResultToJson(result));
  return result;
}

// Each scene's registered images with exhaustive matching, from the
// results.json of a benchmark that ran the scenes alone.
std::map<std::string, size_t> ReadRegisteredAlone(
    const std::string& results_path, const std::set<std::string>& scenes) {
  const Json results = ReadJsonFile(results_path);
  std::map<std::string, size_t> registered;
  for (const Json& scene : results.value("scenes", Json::array())) {
    const std::string name = scene.value("name", std::string());
    if (scenes.count(name) == 0) continue;
    for (const Json& method : scene.value("methods", Json::array())) {
      if (method.value("method", std::string()) == "exhaustive" &&
          method.value("status", std::string()) == "ok") {
        registered[name] = method.at("sfm").value("num_registered", size_t{0});
      }
    }
  }
  for (const std::string& scene : scenes) {
    if (registered.count(scene) == 0) {
      ThrowError("--Benchmark.alone_results_path ",
                 results_path,
                 " has no exhaustive run of the collection's scene ",
                 scene);
    }
  }
  return registered;
}

void WritePrecisionRecallFigure(const std::string& output_path,
                                const std::vector<BenchmarkMethod>& methods,
                                SceneResult* scene) {
  std::map<std::string, PrecisionRecallSeries> series;
  std::vector<std::pair<std::string, std::pair<double, double>>> references;
  for (size_t i = 0; i < methods.size(); ++i) {
    const MethodResult& result = scene->methods[i];
    if (!result.Ok() || result.retrieval.num_pairs == 0) continue;
    if (methods[i].k > 0) {
      PrecisionRecallSeries& s = series[methods[i].pairing];
      s.name = methods[i].pairing;
      s.k.push_back(result.k);
      s.precision.push_back(result.retrieval.precision);
      s.recall.push_back(result.retrieval.recall);
    } else if (methods[i].pairing != "exhaustive") {
      references.emplace_back(
          methods[i].spec,
          std::make_pair(result.retrieval.precision, result.retrieval.recall));
    }
  }
  if (series.empty()) return;
  std::vector<PrecisionRecallSeries> ordered;
  for (auto& [name, s] : series) ordered.push_back(s);
  const std::string relative = "figures/" + scene->name + "/pr_vs_k.png";
  WritePrecisionRecallPlot(JoinPaths(output_path, relative),
                           scene->name + ": precision / recall vs k",
                           ordered,
                           references);
  scene->figures.push_back(relative);
}

SceneResult BenchmarkRunner::RunScene(const DatasetSpec& spec) {
  SceneResult result;
  result.name = spec.name;
  SceneContext scene;
  scene.dir = JoinPaths(options_.output_path, spec.name);
  scene.dataset = PrepareDataset(spec, scene.dir);
  result.kind = scene.dataset.kind;
  Extract(&scene, &result);
  {
    // A cached base.db is read before every method hands a copy of it to
    // COLMAP's matcher and mapper.
    RecoverHotJournal(scene.base_db);
    const Database database(scene.base_db);
    ValidateDatabaseForColmap(database);
    scene.images = database.ReadAllImages();
  }
  for (const DatabaseImage& image : scene.images) {
    scene.names_by_id[image.image_id] = image.name;
    scene.image_names.push_back(image.name);
  }
  std::sort(scene.image_names.begin(), scene.image_names.end());
  result.num_images = scene.images.size();
  result.image_names = scene.image_names;
  result.is_collection = IsMergedCollection(scene.image_names);
  if (result.is_collection && !options_.alone_results_path.empty()) {
    result.registered_alone = ReadRegisteredAlone(
        options_.alone_results_path, CollectionScenes(scene.image_names));
  }
  LoadGroundTruth(&scene);
  result.has_gt_cameras = scene.has_gt;
  // Pair ids repeat between scenes with the same number of images: the
  // pair sets of another scene must never stand in for this one's.
  pair_set_owners_.clear();
  BuildLabels(&scene, &result);

  for (size_t m = 0; m < methods_.size(); ++m) {
    const BenchmarkMethod& method = methods_[m];
    // On small scenes several k are capped to the same N - 1: the pairs
    // are identical, so the first such run stands for the others.
    const int k = method.EffectiveK(scene.images.size());
    bool duplicate = false;
    for (size_t earlier = 0; earlier < m && k > 0 && !duplicate; ++earlier) {
      if (methods_[earlier].pairing == method.pairing &&
          methods_[earlier].EffectiveK(scene.images.size()) == k &&
          result.methods[earlier].Ok()) {
        MethodResult copy = result.methods[earlier];
        copy.method = method.spec;
        copy.message = "same pairs as " + methods_[earlier].spec;
        copy.same_as = methods_[earlier].spec;
        result.methods.push_back(copy);
        duplicate = true;
      }
    }
    if (duplicate) continue;
    Json run = MatchMethod(scene, method);
    if (run.contains("same_as")) {
      const std::string owner = run.at("same_as").get<std::string>();
      for (size_t earlier = 0; earlier < m; ++earlier) {
        if (result.methods[earlier].method != owner) continue;
        MethodResult copy = result.methods[earlier];
        copy.method = method.spec;
        copy.k = static_cast<int>(run.value("k", int64_t{0}));
        copy.pairing_seconds = run.value("pairing_seconds", 0.0);
        copy.message = "same pairs as " + owner;
        copy.same_as = owner;
        result.methods.push_back(copy);
        break;
      }
      if (result.methods.size() == m + 1) continue;
      // The owner is not in this run's results: match after all.
      RemovePath(JoinPaths(MethodDir(scene, method), "run.json"));
      pair_set_owners_.erase(run.value("pairs_hash", std::string()));
      run = MatchMethod(scene, method);
    }
    if (run.value("status", std::string()) == "ok" &&
        run.contains("pairs_hash")) {
      pair_set_owners_.emplace(run.at("pairs_hash").get<std::string>(),
                               method.spec);
    }
    if (run.value("status", std::string()) == "ok") {
      run = MapMethod(scene, method);
    }
    MethodResult method_result = EvaluateMethod(scene, method, run, &result);
    if (method_result.Ok()) {
      const SfmMetrics& sfm = method_result.sfm;
      Progress(
          spec.name,
          method.spec + ": registered " + std::to_string(sfm.num_registered) +
              "/" + std::to_string(sfm.num_images) + " in " +
              std::to_string(sfm.num_models) + " model(s), P " +
              std::to_string(method_result.retrieval.precision).substr(0, 5) +
              " R " +
              std::to_string(method_result.retrieval.recall).substr(0, 5));
    }
    result.methods.push_back(method_result);
  }
  WritePrecisionRecallFigure(options_.output_path, methods_, &result);
  return result;
}

BenchmarkResults BenchmarkRunner::Run() {
  BenchmarkResults results;
  results.command = options_.command;
  results.label_options = options_.labels;
  results.pose_options = options_.pose;
  for (const BenchmarkMethod& method : methods_) {
    results.methods.push_back(method.spec);
  }
  CreateDirIfNotExists(options_.output_path);
  const std::vector<DatasetSpec> specs = ParseDatasetSpecs(options_.datasets);
  for (size_t i = 0; i < specs.size(); ++i) {
    Progress(
        specs[i].name,
        "scene " + std::to_string(i + 1) + "/" + std::to_string(specs.size()));
    try {
      results.scenes.push_back(RunScene(specs[i]));
    } catch (const Error& error) {
      // An interrupted run stops here; the cache keeps what was complete.
      if (PendingInterrupt() != 0) throw;
      // One broken scene must not cost the others' results.
      SceneResult failed;
      failed.name = specs[i].name;
      failed.status = "failed";
      failed.message = error.what();
      Progress(specs[i].name, std::string("FAILED: ") + error.what());
      results.scenes.push_back(failed);
    }
    // The report is rewritten after every scene: partial results are
    // readable while a long run continues.
    WriteBenchmarkReport(results, options_.output_path);
  }
  return results;
}

}  // namespace

PairMatchingOptions BenchmarkOptions::MatchingOptions() const {
  PairMatchingOptions matching;
  matching.colmap_args = matching_args;
  matching.min_num_inliers = gcn_matching.matching.min_num_inliers;
  return matching;
}

void BenchmarkOptions::Check() const {
  CHECK_OPTION(datasets, !datasets.empty(), "name at least one dataset");
  CHECK_OPTION(methods, !methods.empty(), "name methods (or none)");
  CHECK_OPTION(output_path, !output_path.empty(), "name a folder");
  labels.Check();
  pose.Check();
  label_pair_filter.Check();
  CHECK_OPTION_GE(single_camera, -1);
  CHECK_OPTION_NUM_THREADS(mapper_num_threads);
  CHECK_OPTION_GE(mapper_min_model_size, 0);
  CHECK_OPTION(alone_results_path,
               alone_results_path.empty() || ExistsFile(alone_results_path),
               "no such file");
  // The options of every generator a method uses, before any work.
  for (const BenchmarkMethod& method : ParseBenchmarkMethods(methods)) {
    if (!method.IsOracle()) {
      PairGenerators().Check(method.pairing, gcn_matching.generators);
    }
  }
  gcn_matching.matching.Check();
}

namespace {

std::vector<std::string> BenchmarkDatasetProblems(
    const BenchmarkOptions& options) {
  std::vector<std::string> problems;
  for (const DatasetSpec& spec : ParseDatasetSpecs(options.datasets)) {
    try {
      CheckDataset(spec);
    } catch (const Error& error) {
      problems.push_back(error.what());
    }
  }
  return problems;
}

}  // namespace

BenchmarkResults RunBenchmark(const BenchmarkOptions& options) {
  options.Check();
  ParseBenchmarkMethods(options.methods);
  const std::vector<std::string> problems = BenchmarkDatasetProblems(options);
  if (!problems.empty()) {
    ThrowError(StringJoin(problems, "; "));
  }
  return BenchmarkRunner(options).Run();
}

std::vector<std::string> BenchmarkFailures(const BenchmarkResults& results) {
  std::vector<std::string> failures;
  for (const SceneResult& scene : results.scenes) {
    if (scene.status != "ok") {
      failures.push_back(scene.name + ": " + scene.message);
      continue;
    }
    for (const MethodResult& method : scene.methods) {
      if (!method.Ok()) {
        failures.push_back(scene.name + "/" + method.method + " " +
                           method.status + ": " + method.message);
      }
    }
  }
  return failures;
}

}  // namespace colmap_gcn

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
#include "controllers/pair_generators.h"
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
#include "evaluation/view_graph_figure.h"
#include "pairing/imported_pairing.h"
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

std::unique_ptr<PairGenerator> BenchmarkRunner::CreateGenerator(
    const SceneContext& scene,
    const BenchmarkMethod& method,
    double* prepare_seconds) const {
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
  // What a user has before pairing (a downloaded vocabulary tree) is made
  // here and not counted as pairing.
  const Timer prepare_timer;
  if (registry.Prepare(method.pairing, &options, context)) {
    *prepare_seconds = prepare_timer.ElapsedSeconds();
  }
  return registry.Create(method.pairing, options, context);
}

namespace {

// The look-alike filter's state as --GcnMatching.filter_lookalikes asks:
// applied to a freshly matched database, or applied / undone on a cached one
// (which then maps again). Records it in `run`.
void ApplyLookalikeFilter(const std::string& db,
                          const GcnMatchingOptions& gcn_matching,
                          Json* run) {
  const bool wanted = gcn_matching.filter_lookalikes;
  if (run->value("status", std::string()) != "ok" || run->contains("same_as") ||
      (run->contains("lookalike_filter") &&
       run->at("lookalike_filter").get<bool>() == wanted)) {
    return;
  }
  if (wanted) {
    PairFilterOptions options = gcn_matching.lookalike_filter;
    options.min_num_inliers = gcn_matching.matching.min_num_inliers;
    const PairFilterReport report = FilterLookalikePairs(db, options);
    (*run)["lookalike_removed"] = report.num_rejected;
    (*run)["filter_seconds"] = report.seconds;
  } else {
    RestoreLookalikePairs(db);
    run->erase("lookalike_removed");
    run->erase("filter_seconds");
  }
  (*run)["lookalike_filter"] = wanted;
  run->erase("mapping_seconds");  // maps again
}

}  // namespace

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
      const Json before = run;
      ApplyLookalikeFilter(
          JoinPaths(dir, "database.db"), options_.gcn_matching, &run);
      if (run != before) WriteJsonFile(run_path, run);
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
  double prepare_seconds = 0;
  try {
    generator = CreateGenerator(scene, method, &prepare_seconds);
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
  run["pairing_seconds"] = pairing_timer.ElapsedSeconds() - prepare_seconds;
  if (prepare_seconds > 0) run["prepare_seconds"] = prepare_seconds;
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
    ApplyLookalikeFilter(db, options_.gcn_matching, &run);
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

std::vector<ImageNamePair> BenchmarkRunner::CountLookalikeRemovals(
    const std::string& db,
    const SceneContext& scene,
    MethodResult* result) const {
  const std::vector<ImageNamePair> hidden =
      ReadHiddenImagePairs(db, options_.gcn_matching.matching.min_num_inliers);
  result->num_lookalike_removed = hidden.size();
  for (const auto& [name1, name2] : hidden) {
    if (!scene.labels.IsLabelled(name1, name2)) continue;
    if (scene.labels.SharesNothing(name1, name2)) {
      ++result->num_lookalike_removed_wrong;
    }
    if (scene.labels.IsMatchable(name1, name2, options_.labels)) {
      ++result->num_lookalike_removed_matchable;
    }
  }
  RemoveEmptySqliteSideFiles(db);
  return hidden;
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
  result.prepare_seconds = run.value("prepare_seconds", 0.0);
  result.matching_seconds = run.value("matching_seconds", 0.0);
  result.mapping_seconds = run.value("mapping_seconds", 0.0);
  result.num_attempted = run.value("tam", size_t{0});
  result.num_verified = run.value("um", size_t{0});
  result.lookalike_filter = run.value("lookalike_filter", false);
  result.filter_seconds = run.value("filter_seconds", 0.0);
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
  const std::vector<ImageNamePair> hidden =
      CountLookalikeRemovals(JoinPaths(dir, "database.db"), scene, &result);
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
                      hidden,
                      scene.labels,
                      options_.labels);
  scene_result->figures.push_back("figures/" + scene.dataset.name + "/" +
                                  figure);
  WriteJsonFile(JoinPaths(dir, "result.json"), MethodResultToJson(result));
  return result;
}

}  // namespace internal
}  // namespace colmap_gcn

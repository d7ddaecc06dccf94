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
namespace {

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

}  // namespace

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

const ColmapRunner& BenchmarkRunner::Colmap(const SceneContext& scene) {
  const std::string log_path = JoinPaths(scene.dir, "colmap.log");
  if (!colmap_ || colmap_log_ != log_path) {
    ColmapRunnerOptions runner_options;
    runner_options.colmap_exe = options_.colmap_exe;
    runner_options.log_path = log_path;
    runner_options.verbose = options_.verbose;
    colmap_ = std::make_unique<ColmapRunner>(runner_options);
    colmap_log_ = log_path;
  }
  return *colmap_;
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

  ProgressLogger method_progress(
      methods_.size(), scene.dataset.name + ": methods", "methods");
  for (size_t m = 0; m < methods_.size(); ++m) {
    method_progress.Update(m);
    const BenchmarkMethod& method = methods_[m];
    Progress(scene.dataset.name,
             "method " + std::to_string(m + 1) + "/" +
                 std::to_string(methods_.size()) + ": " + method.spec);
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
        copy.prepare_seconds = run.value("prepare_seconds", 0.0);
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
  method_progress.Update(methods_.size());
  WritePrecisionRecallFigure(options_.output_path, methods_, &result);
  // Every method read base.db: leave the scene folder without the empty
  // "-wal"/"-shm" those reads leave beside it.
  RemoveEmptySqliteSideFiles(scene.base_db);
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
  ProgressLogger progress(specs.size(), "benchmark", "scenes");
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
    progress.Increment();
  }
  return results;
}

}  // namespace internal
}  // namespace colmap_gcn

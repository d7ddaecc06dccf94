#pragma once

// The benchmark's implementation, shared by evaluation/benchmark*.cc only:
// RunBenchmark (benchmark.h) is the interface. benchmark_runner.cc runs the
// scenes and their methods, benchmark_scene.cc prepares a scene (features,
// ground truth, labels), benchmark_methods.cc runs one method (matching,
// mapping, evaluation, each cached per method folder).

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "controllers/colmap_runner.h"
#include "evaluation/benchmark.h"
#include "evaluation/dataset.h"
#include "evaluation/json_file.h"
#include "evaluation/labels.h"
#include "evaluation/method.h"
#include "pairing/pairing.h"
#include "scene/database.h"
#include "scene/reconstruction.h"
#include "util/file.h"

namespace colmap_gcn {
namespace internal {

// One progress line of a scene: "<scene>: <message>".
void Progress(const std::string& scene, const std::string& message);

// "12.3 s".
std::string FormatSeconds(double seconds);

// Identifies one benchmark invocation; stored with every matching result so
// the report can tell when cached times come from different runs.
std::string NewSessionId();

// Removes a file or folder if it exists.
void RemovePath(const std::string& path);

// A fresh database for one method: the scene's extracted base, with no
// working copy of an earlier interrupted run beside it.
void CopyBaseDatabase(const std::string& from, const std::string& to);

// Identifies a pair set regardless of order and orientation.
std::string PairSetHash(const std::vector<ImagePair>& pairs);

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
  // The pairs the look-alike filter hid in a method's database, counted by
  // label; returns them.
  std::vector<ImageNamePair> CountLookalikeRemovals(const std::string& db,
                                                    const SceneContext& scene,
                                                    MethodResult* result) const;
  MethodResult EvaluateMethod(const SceneContext& scene,
                              const BenchmarkMethod& method,
                              const Json& run,
                              SceneResult* scene_result);
  // Runs the generator's prepare step first (PairGeneratorSpec::prepare),
  // its time in *prepare_seconds.
  std::unique_ptr<PairGenerator> CreateGenerator(const SceneContext& scene,
                                                 const BenchmarkMethod& method,
                                                 double* prepare_seconds) const;
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

}  // namespace internal
}  // namespace colmap_gcn

// Retrieval quality on real scenes with GT cameras (prints numbers; not a
// test):
//   retrieval_quality WORK_DIR SCENE_DIR...
// For each scene (SCENE_DIR/images, SCENE_DIR/gt): COLMAP feature_extractor
// and exhaustive_matcher into WORK_DIR/<scene>/database.db (kept for
// re-runs), labels from GT-camera triangulation (common-track ratio,
// tau = 0.15), then precision/recall of
//   - kNN top-k on the self-trained VLAD embedding (several whitening
//     shrinkages),
//   - COLMAP's vocabulary tree (tree built from the scene itself),
// for k = 5, 10, 25 (capped at N - 1).
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "controllers/colmap_runner.h"
#include "controllers/vocab_tree_pairing.h"
#include "evaluation/metrics.h"
#include "evaluation/pair_labels.h"
#include "pairing/knn_pairing.h"
#include "retrieval/global_descriptors.h"
#include "scene/database.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

std::vector<ImageNamePair> ToNames(const std::vector<ImagePair>& pairs,
                                   const Database& database) {
  std::map<image_t, std::string> names;
  for (const auto& image : database.ReadAllImages()) {
    names[image.image_id] = image.name;
  }
  std::vector<ImageNamePair> named;
  for (const auto& [a, b] : pairs) named.emplace_back(names[a], names[b]);
  return named;
}

void RunScene(const ColmapRunner& colmap,
              const std::string& work_dir,
              const std::string& scene_dir) {
  std::string scene = scene_dir;
  while (!scene.empty() && scene.back() == '/') scene.pop_back();
  scene = scene.substr(scene.find_last_of('/') + 1);
  const std::string dir = JoinPaths(work_dir, scene);
  CreateDirIfNotExists(dir);
  const std::string database_path = JoinPaths(dir, "database.db");
  if (!ExistsFile(database_path)) {
    colmap.Run("feature_extractor",
               {"--database_path",
                database_path + ".tmp",
                "--image_path",
                JoinPaths(scene_dir, "images"),
                "--SiftExtraction.num_threads",
                "2"});
    colmap.Run("exhaustive_matcher",
               {"--database_path",
                database_path + ".tmp",
                "--SiftMatching.num_threads",
                "2"});
    std::rename((database_path + ".tmp").c_str(), database_path.c_str());
  }
  const std::string labels_path = JoinPaths(dir, "labels.csv");
  PairLabels labels;
  if (ExistsFile(labels_path)) {
    labels = PairLabels::Read(labels_path);
  } else {
    labels = ComputeGroundTruthCameraLabels(colmap,
                                            database_path,
                                            JoinPaths(scene_dir, "gt"),
                                            JoinPaths(dir, "gt_triangulation"));
    labels.Write(labels_path);
  }
  const PairLabelOptions label_options;  // tau_CT = 0.15
  const Database database(database_path);
  const std::vector<DatabaseImage> images = database.ReadAllImages();
  std::vector<std::string> names;
  for (const auto& image : images) names.push_back(image.name);
  const int n = static_cast<int>(images.size());
  std::printf("\n%s: %d images, %zu matchable pairs (CT >= %.2f) of %d\n",
              scene.c_str(),
              n,
              labels.MatchablePairs(label_options).size(),
              label_options.min_common_track_ratio,
              n * (n - 1) / 2);
  std::printf("%-28s %4s %8s %8s %8s | %6s %6s %6s\n",
              "method",
              "k",
              "P_query",
              "R_query",
              "hit",
              "pairs",
              "P_pair",
              "R_pair");
  for (const double shrinkage : {0.0, 0.3, 1.0, 3.0, 1e6}) {
    GlobalDescriptorOptions options;
    options.vlad.self_training_shrinkage = shrinkage;
    options.use_cache = false;
    std::vector<image_t> image_ids;
    const EmbeddingMatrix embeddings =
        ComputeGlobalDescriptors(database, options, &image_ids);
    KnnOptions knn_options;
    knn_options.k = n - 1;
    const KnnGraph graph = ComputeExactKnn(embeddings, knn_options);
    for (const int k : {5, 10, 25}) {
      if (k > n - 1 && k != 5) continue;
      const TopKRetrievalScores scores =
          ScoreTopKRetrieval(graph, names, k, labels, label_options);
      KnnOptions top_k = knn_options;
      top_k.k = k;
      const PairSetScore pair_metrics = ComputeRetrievalMetrics(
          ToNames(
              KnnGraphToPairs(ComputeExactKnn(embeddings, top_k), image_ids),
              database),
          labels,
          label_options);
      char method[64];
      std::snprintf(method,
                    sizeof(method),
                    "vlad-knn shrink=%g dim=%d",
                    shrinkage,
                    static_cast<int>(embeddings.cols()));
      std::printf("%-28s %4d %8.3f %8.3f %8.3f | %6zu %6.3f %6.3f\n",
                  method,
                  scores.k,
                  scores.mean_precision,
                  scores.mean_recall,
                  scores.hit_rate,
                  pair_metrics.num_pairs,
                  pair_metrics.precision,
                  pair_metrics.recall);
    }
  }
  for (const int k : {5, 10, 25}) {
    if (k > n - 1 && k != 5) continue;
    VocabTreePairingOptions options;
    options.k = k;
    VocabTreePairGenerator generator(options, database, colmap);
    const PairSetScore metrics = ComputeRetrievalMetrics(
        ToNames(generator.AllPairs(), database), labels, label_options);
    std::printf("%-28s %4d %8s %8s %8s | %6zu %6.3f %6.3f\n",
                "vocab_tree (self-built)",
                std::min(k, n - 1),
                "-",
                "-",
                "-",
                metrics.num_pairs,
                metrics.precision,
                metrics.recall);
  }
}

}  // namespace
}  // namespace colmap_gcn

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: retrieval_quality WORK_DIR SCENE_DIR...\n");
    return 1;
  }
  try {
    colmap_gcn::ColmapRunnerOptions runner_options;
    runner_options.show_progress = false;
    const colmap_gcn::ColmapRunner colmap(runner_options);
    for (int i = 2; i < argc; ++i) {
      colmap_gcn::RunScene(colmap, argv[1], argv[i]);
    }
  } catch (const colmap_gcn::Error& error) {
    std::fprintf(stderr, "ERROR: %s\n", error.what());
    return 1;
  }
  return 0;
}

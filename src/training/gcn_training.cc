#include "training/gcn_training.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "gcn/gcn_pair_generator.h"
#include "retrieval/embedding_cache.h"
#include "retrieval/knn_pairing.h"
#include "scene/database.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

uint64_t PairKey(int i, int j) {
  return (static_cast<uint64_t>(std::min(i, j)) << 32) |
         static_cast<uint32_t>(std::max(i, j));
}

std::unordered_set<uint64_t> PairKeys(
    const std::vector<std::pair<int, int>>& pairs) {
  std::unordered_set<uint64_t> keys;
  for (const auto& [i, j] : pairs) keys.insert(PairKey(i, j));
  return keys;
}

}  // namespace

std::vector<LabelledScene> FindLabelledScenes(
    const std::string& benchmark_path, const std::vector<std::string>& names) {
  if (!ExistsDir(benchmark_path)) {
    ThrowError("benchmark folder not found: ", benchmark_path);
  }
  auto scene_at = [&](const std::string& name) {
    LabelledScene scene;
    scene.name = name;
    scene.database_path = JoinPaths(JoinPaths(benchmark_path, name), "base.db");
    scene.labels_path =
        JoinPaths(JoinPaths(benchmark_path, name), "labels/labels.csv");
    return scene;
  };
  std::vector<LabelledScene> scenes;
  if (names.empty()) {
    std::vector<std::string> found;
    for (const auto& entry :
         std::filesystem::directory_iterator(benchmark_path)) {
      found.push_back(entry.path().filename().string());
    }
    std::sort(found.begin(), found.end());
    for (const auto& name : found) {
      const LabelledScene scene = scene_at(name);
      if (ExistsFile(scene.database_path) && ExistsFile(scene.labels_path)) {
        scenes.push_back(scene);
      }
    }
  } else {
    auto prepared_scene_at = [&](const std::string& name) {
      const LabelledScene scene = scene_at(name);
      if (!ExistsFile(scene.database_path) || !ExistsFile(scene.labels_path)) {
        ThrowError("scene ",
                   name,
                   " in ",
                   benchmark_path,
                   " has no base.db and labels/labels.csv; prepare it with "
                   "colmap gcn_benchmark --methods oracle");
      }
      return scene;
    };
    for (const auto& name : names) {
      if (name.find('+') == std::string::npos) {
        scenes.push_back(prepared_scene_at(name));
        continue;
      }
      LabelledScene collection;
      collection.name = name;
      std::set<std::string> seen;
      for (const auto& part : StringSplit(name, "+")) {
        if (part.empty() || !seen.insert(part).second) {
          ThrowError("collection ", name, " needs distinct scene names");
        }
        collection.parts.push_back(prepared_scene_at(part));
      }
      scenes.push_back(collection);
    }
  }
  if (scenes.empty()) {
    ThrowError("no labelled scenes in ", benchmark_path);
  }
  return scenes;
}

std::vector<LabelledScene> WithoutHeldOutScenes(
    const std::vector<LabelledScene>& scenes,
    const std::vector<std::string>& held_out) {
  std::set<std::string> held_out_scenes;
  for (const auto& name : held_out) {
    for (const auto& part : StringSplit(name, "+")) {
      held_out_scenes.insert(part);
    }
  }
  std::vector<LabelledScene> kept;
  for (const auto& scene : scenes) {
    bool shares = false;
    for (const auto& part : StringSplit(scene.name, "+")) {
      shares = shares || held_out_scenes.count(part) > 0;
    }
    if (!shares) kept.push_back(scene);
  }
  return kept;
}

void GcnTrainingPipelineOptions::Check() const {
  CHECK_OPTION_ONE_OF(embedding, "vlad", "onnx", "vlad+onnx");
  vlad.Check();
  cnn.Check();
  if (embedding != "vlad") {
    CHECK_OPTION(cnn.onnx_path,
                 !cnn.onnx_path.empty(),
                 "name the ONNX network when the embedding is " + embedding);
    CHECK_OPTION(images.image_root,
                 ExistsDir(images.image_root),
                 "be a folder with one subfolder <scene>/images per scene");
  }
  labels.Check();
  training.Check();
  CHECK_OPTION(threshold,
               threshold < 0 || (threshold > 0 && threshold < 1),
               "be < 0 (chosen on the validation scenes) or in (0, 1)");
}

GcnTrainingScene MergeTrainingScenes(
    const std::string& name, const std::vector<GcnTrainingScene>& parts) {
  GcnTrainingScene merged;
  merged.name = name;
  if (parts.empty()) return merged;
  const Eigen::Index dim = parts.front().embeddings.cols();
  Eigen::Index num_rows = 0;
  for (const auto& part : parts) {
    if (part.embeddings.cols() != dim) {
      ThrowError("collection ", name, " mixes embedding dimensions");
    }
    num_rows += part.embeddings.rows();
  }
  merged.embeddings.resize(num_rows, dim);
  Eigen::Index offset = 0;
  for (size_t p = 0; p < parts.size(); ++p) {
    const GcnTrainingScene& part = parts[p];
    const int first = static_cast<int>(offset);
    merged.part_of_row.insert(
        merged.part_of_row.end(), part.embeddings.rows(), static_cast<int>(p));
    merged.embeddings.middleRows(offset, part.embeddings.rows()) =
        part.embeddings;
    for (const auto& [i, j] : part.positive_pairs) {
      merged.positive_pairs.emplace_back(first + i, first + j);
    }
    for (const auto& [i, j] : part.unrelated_pairs) {
      merged.unrelated_pairs.emplace_back(first + i, first + j);
    }
    // Every image of this part against every image of the earlier parts.
    for (int i = 0; i < first; ++i) {
      for (Eigen::Index j = 0; j < part.embeddings.rows(); ++j) {
        merged.unrelated_pairs.emplace_back(i, first + static_cast<int>(j));
      }
    }
    offset += part.embeddings.rows();
  }
  return merged;
}

namespace {

typedef std::function<EmbeddingMatrix(
    const LabelledScene&, const Database&, std::vector<image_t>*)>
    EmbedDatabaseFunction;

// The scene (or collection) with rows as embed_database gives them.
GcnTrainingScene MakeUnfinalizedTrainingScene(
    const LabelledScene& scene,
    const EmbedDatabaseFunction& embed_database,
    const PairLabelOptions& label_options) {
  if (!scene.parts.empty()) {
    std::vector<GcnTrainingScene> parts;
    for (const auto& part : scene.parts) {
      parts.push_back(
          MakeUnfinalizedTrainingScene(part, embed_database, label_options));
    }
    return MergeTrainingScenes(scene.name, parts);
  }
  const Database database(scene.database_path);
  const PairLabels labels = PairLabels::Read(scene.labels_path);
  std::vector<image_t> image_ids;
  GcnTrainingScene training_scene;
  training_scene.name = scene.name;
  training_scene.embeddings = embed_database(scene, database, &image_ids);
  std::unordered_map<image_t, int> row_of_id;
  for (size_t row = 0; row < image_ids.size(); ++row) {
    row_of_id.emplace(image_ids[row], static_cast<int>(row));
  }
  std::unordered_map<std::string, int> row_of_name;
  for (const auto& image : database.ReadAllImages()) {
    row_of_name.emplace(image.name, row_of_id.at(image.image_id));
  }
  for (const auto& [name1, name2] : labels.MatchablePairs(label_options)) {
    const auto it1 = row_of_name.find(name1);
    const auto it2 = row_of_name.find(name2);
    if (it1 != row_of_name.end() && it2 != row_of_name.end()) {
      training_scene.positive_pairs.emplace_back(it1->second, it2->second);
    }
  }
  std::vector<std::pair<std::string, int>> rows(row_of_name.begin(),
                                                row_of_name.end());
  std::sort(rows.begin(), rows.end());
  for (size_t a = 0; a < rows.size(); ++a) {
    for (size_t b = a + 1; b < rows.size(); ++b) {
      if (labels.SharesNothing(rows[a].first, rows[b].first)) {
        training_scene.unrelated_pairs.emplace_back(rows[a].second,
                                                    rows[b].second);
      }
    }
  }
  return training_scene;
}

}  // namespace

std::string SceneImageOptions::ImagePath(const LabelledScene& scene) const {
  return JoinPaths(JoinPaths(image_root, scene.name), "images");
}

std::string SceneImageOptions::CnnCachePath(const LabelledScene& scene) const {
  return cnn_cache_dir.empty()
             ? DefaultCnnCachePath(scene.database_path)
             : JoinPaths(cnn_cache_dir, scene.name + ".gcn-cnn-embedding.bin");
}

GcnTrainingScene MakeTrainingScene(const LabelledScene& scene,
                                   const VladEmbedding& vlad,
                                   const PairLabelOptions& label_options,
                                   int num_threads) {
  return MakeUnfinalizedTrainingScene(
      scene,
      [&](const LabelledScene&,
          const Database& database,
          std::vector<image_t>* image_ids) {
        return ComputeDatabaseEmbeddings(
            database, vlad, image_ids, /*cache_path=*/"", num_threads);
      },
      label_options);
}

GcnTrainingScene MakeTrainingScene(const LabelledScene& scene,
                                   const ModelEmbedder& embedder,
                                   const SceneImageOptions& images,
                                   const PairLabelOptions& label_options) {
  GcnTrainingScene made = MakeUnfinalizedTrainingScene(
      scene,
      [&](const LabelledScene& part,
          const Database& database,
          std::vector<image_t>* image_ids) {
        return embedder.EmbedDatabase(database,
                                      images.ImagePath(part),
                                      images.CnnCachePath(part),
                                      image_ids);
      },
      label_options);
  made.embeddings = embedder.Finalize(made.embeddings);
  return made;
}

GcnModel TrainGcnModel(const std::vector<LabelledScene>& training_scenes,
                       const std::vector<LabelledScene>& validation_scenes,
                       const GcnTrainingPipelineOptions& options) {
  options.Check();
  // Each database once, in order, whether a scene or a collection's part.
  std::vector<std::string> database_paths;
  std::set<std::string> seen;
  for (const auto& scene : training_scenes) {
    for (const auto& part : scene.parts.empty()
                                ? std::vector<LabelledScene>{scene}
                                : scene.parts) {
      if (seen.insert(part.database_path).second) {
        database_paths.push_back(part.database_path);
      }
    }
  }
  const bool use_vlad = options.embedding != "onnx";
  const bool use_cnn = options.embedding != "vlad";
  VladEmbedding vlad;
  if (use_vlad) {
    LOG(INFO) << "training the VLAD embedding on " << database_paths.size()
              << " databases";
    vlad = TrainVladEmbedding(database_paths, options.vlad);
  }
  CnnEmbeddingModel cnn_model;
  if (use_cnn) {
    // Raw descriptors of every training database (cached, so embedding the
    // scenes below reuses them), then the PCA on them.
    const CnnNetwork network(options.cnn);
    std::vector<FloatMatrix> collections;
    std::set<std::string> embedded;
    for (const auto& scene : training_scenes) {
      for (const auto& part : scene.parts.empty()
                                  ? std::vector<LabelledScene>{scene}
                                  : scene.parts) {
        if (!embedded.insert(part.database_path).second) continue;
        LOG(INFO) << "CNN descriptors of " << part.name;
        std::vector<image_t> image_ids;
        collections.push_back(
            ComputeDatabaseCnnDescriptors(Database(part.database_path),
                                          network,
                                          options.images.ImagePath(part),
                                          options.images.CnnCachePath(part),
                                          &image_ids));
      }
    }
    cnn_model = TrainCnnEmbeddingModel(network, collections);
    LOG(INFO) << "CNN embedding " << cnn_model.network_name << " (checksum "
              << FormatChecksum(cnn_model.network_checksum)
              << "): " << cnn_model.descriptor_dim << " -> "
              << cnn_model.OutputDim() << "-D";
  }
  const GcnEmbeddingConfig embedding_config = MakeEmbeddingConfig(
      use_vlad ? &vlad : nullptr, use_cnn ? &cnn_model : nullptr);
  ModelEmbeddingOptions embedder_options;
  embedder_options.onnx_path = options.cnn.onnx_path;
  embedder_options.onnx_flag = "--GcnTraining.onnx_path";
  embedder_options.onnx_batch_size = options.cnn.batch_size;
  embedder_options.num_threads = options.training.num_threads;
  embedder_options.progress_every = options.cnn.progress_every;
  embedder_options.use_vlad_cache = false;
  const ModelEmbedder embedder(embedding_config, embedder_options);

  auto make_scenes = [&](const std::vector<LabelledScene>& scenes) {
    std::vector<GcnTrainingScene> made;
    for (const auto& scene : scenes) {
      made.push_back(
          MakeTrainingScene(scene, embedder, options.images, options.labels));
      LOG(INFO) << "scene " << scene.name << ": "
                << made.back().embeddings.rows() << " images, "
                << made.back().positive_pairs.size() << " matchable pairs";
    }
    return made;
  };
  const std::vector<GcnTrainingScene> train = make_scenes(training_scenes);
  const std::vector<GcnTrainingScene> validation =
      make_scenes(validation_scenes);

  GcnTrainingOptions training = options.training;
  // A fixed threshold is also the one the epoch statistics use.
  if (options.threshold > 0) {
    training.threshold = static_cast<float>(options.threshold);
  }
  training.tau_mo = static_cast<float>(options.labels.min_overlap);
  training.tau_ct = static_cast<float>(options.labels.min_common_track_ratio);
  GcnTrainer trainer(training);
  GcnModel model = trainer.Train(train, validation);
  model.embedding = embedding_config;
  if (options.threshold >= 0) {
    model.info.threshold = static_cast<float>(options.threshold);
  } else {
    // Chosen on held-out data when there is some: on the training scenes
    // the network's scores are optimistic.
    const std::vector<GcnTrainingScene>& selection =
        validation.empty() ? train : validation;
    model.info.threshold =
        SelectGcnThreshold(model, selection, options.training.num_threads);
    LOG(INFO) << "decision threshold " << std::to_string(model.info.threshold)
              << " (max mean F on the "
              << (validation.empty() ? "training" : "validation") << " scenes)";
  }
  std::ostringstream notes;
  notes << "trained on";
  for (const auto& scene : training_scenes) notes << " " << scene.name;
  if (!validation_scenes.empty()) {
    notes << "; validated on";
    for (const auto& scene : validation_scenes) notes << " " << scene.name;
  }
  if (use_vlad) {
    notes << "; VLAD " << vlad.NumWords() << " words -> " << vlad.OutputDim()
          << "-D";
  }
  if (use_cnn) {
    notes << "; CNN " << cnn_model.network_name << " (checksum "
          << FormatChecksum(cnn_model.network_checksum) << ", "
          << cnn_model.options.max_image_size << " px, GeM p "
          << cnn_model.options.gem_p
          << (cnn_model.options.center ? ", centred" : "") << ") -> "
          << cnn_model.OutputDim() << "-D";
  }
  notes << "; tau_MO " << options.labels.min_overlap << ", tau_CT "
        << options.labels.min_common_track_ratio << "; threshold "
        << model.info.threshold << "; seed " << training.seed;
  model.info.notes = notes.str();
  return model;
}

PrecisionRecall PairSetScores::Scores() const {
  return ComputePrecisionRecall(num_true_positives, num_pairs, num_positives);
}

double PairSetScores::Precision() const { return Scores().precision; }

double PairSetScores::Recall() const { return Scores().recall; }

double PairSetScores::F() const { return Scores().f_measure; }

PairSetScores ScorePairSet(const std::vector<std::pair<int, int>>& pairs,
                           const GcnTrainingScene& scene) {
  const std::unordered_set<uint64_t> positives = PairKeys(scene.positive_pairs);
  const std::unordered_set<uint64_t> unrelated =
      PairKeys(scene.unrelated_pairs);
  std::unordered_set<uint64_t> selected;
  for (const auto& [i, j] : pairs) {
    if (i != j) selected.insert(PairKey(i, j));
  }
  PairSetScores scores;
  scores.num_pairs = selected.size();
  scores.num_positives = positives.size();
  for (const uint64_t key : selected) {
    scores.num_true_positives += positives.count(key);
    scores.num_unrelated += unrelated.count(key);
  }
  if (!scene.part_of_row.empty()) {
    for (const auto& [i, j] : pairs) {
      // Each distinct pair once: its key leaves the set when counted.
      if (i != j && scene.part_of_row[i] != scene.part_of_row[j] &&
          selected.erase(PairKey(i, j)) > 0) {
        ++scores.num_cross_scene;
      }
    }
  }
  return scores;
}

std::vector<std::pair<int, int>> MostSimilarPairs(
    const EmbeddingMatrix& embeddings, size_t num_pairs) {
  const int n = static_cast<int>(embeddings.rows());
  const Eigen::MatrixXf similarity = embeddings * embeddings.transpose();
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) pairs.emplace_back(i, j);
  }
  num_pairs = std::min(num_pairs, pairs.size());
  std::partial_sort(pairs.begin(),
                    pairs.begin() + num_pairs,
                    pairs.end(),
                    [&](const auto& a, const auto& b) {
                      const float sa = similarity(a.first, a.second);
                      const float sb = similarity(b.first, b.second);
                      return sa != sb ? sa > sb : a < b;
                    });
  pairs.resize(num_pairs);
  return pairs;
}

std::vector<std::pair<int, int>> ShortestPrefixWithTruePositives(
    std::vector<std::pair<int, int>> ranked,
    const GcnTrainingScene& scene,
    size_t num_true_positives) {
  const std::unordered_set<uint64_t> positives = PairKeys(scene.positive_pairs);
  size_t prefix = 0;
  for (size_t found = 0; prefix < ranked.size() && found < num_true_positives;
       ++prefix) {
    found +=
        positives.count(PairKey(ranked[prefix].first, ranked[prefix].second));
  }
  ranked.resize(prefix);
  return ranked;
}

double BestPrecisionAtRecall(const std::vector<std::pair<int, int>>& ranked,
                             const GcnTrainingScene& scene,
                             double min_recall) {
  const std::unordered_set<uint64_t> positives = PairKeys(scene.positive_pairs);
  if (positives.empty()) return -1;
  std::unordered_set<uint64_t> seen;
  size_t num_true_positives = 0;
  double best = -1;
  for (const auto& [i, j] : ranked) {
    const uint64_t key = PairKey(i, j);
    if (i == j || !seen.insert(key).second) continue;
    num_true_positives += positives.count(key);
    const double recall =
        static_cast<double>(num_true_positives) / positives.size();
    if (recall >= min_recall) {
      best =
          std::max(best, static_cast<double>(num_true_positives) / seen.size());
    }
  }
  return best;
}

std::vector<std::pair<int, int>> TopKPairs(const KnnGraph& graph, int k) {
  const int n = graph.NumImages();
  k = std::min(k, graph.K());
  if (n < 2 || k <= 0) return {};
  // Rows are sorted by similarity: the top-k graph is the first k columns.
  KnnGraph top_k;
  top_k.indices = graph.indices.leftCols(k);
  top_k.similarities = graph.similarities.leftCols(k);
  // KnnPairGenerator's selection, with row indices as image ids.
  std::vector<image_t> rows(n);
  for (int i = 0; i < n; ++i) rows[i] = static_cast<image_t>(i);
  std::vector<std::pair<int, int>> pairs;
  for (const auto& [i, j] : KnnGraphToPairs(top_k, rows)) {
    pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
  }
  return pairs;
}

std::vector<std::pair<int, int>> TopKPairs(const EmbeddingMatrix& embeddings,
                                           int k,
                                           int num_threads) {
  const int n = static_cast<int>(embeddings.rows());
  if (n < 2 || k <= 0) return {};
  KnnOptions knn_options;
  knn_options.k = std::min(k, n - 1);
  knn_options.num_threads = num_threads;
  return TopKPairs(ComputeExactKnn(embeddings, knn_options), k);
}

std::vector<ScoredRowPair> GcnCandidatePairs(const GcnModel& model,
                                             const GcnTrainingScene& scene,
                                             int num_threads) {
  GcnPairingOptions options = GcnPairingOptionsFromModel(model);
  options.threshold = 0;
  options.min_pairs_per_image = 0;
  options.num_threads = num_threads;
  std::vector<image_t> ids(scene.embeddings.rows());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<image_t>(i + 1);
  GcnPairGenerator generator(options, ids, scene.embeddings, model);
  std::vector<ScoredRowPair> candidates;
  for (const auto& pair : generator.ScoredPairs()) {
    candidates.push_back({static_cast<int>(pair.image_id1) - 1,
                          static_cast<int>(pair.image_id2) - 1,
                          pair.score});
  }
  return candidates;
}

std::vector<uint8_t> MatchableFlags(
    const std::vector<ScoredRowPair>& candidates,
    const GcnTrainingScene& scene) {
  const std::unordered_set<uint64_t> positives = PairKeys(scene.positive_pairs);
  std::vector<uint8_t> flags;
  flags.reserve(candidates.size());
  for (const auto& candidate : candidates) {
    flags.push_back(positives.count(PairKey(candidate.row1, candidate.row2)));
  }
  return flags;
}

std::vector<std::pair<int, int>> PairsAtThreshold(
    const std::vector<ScoredRowPair>& candidates, float threshold) {
  std::vector<std::pair<int, int>> pairs;
  for (const auto& candidate : candidates) {
    if (candidate.score >= threshold) {
      pairs.emplace_back(candidate.row1, candidate.row2);
    }
  }
  return pairs;
}

float SelectGcnThreshold(const GcnModel& model,
                         const std::vector<GcnTrainingScene>& scenes,
                         int num_threads) {
  if (scenes.empty()) return model.info.threshold;
  std::vector<std::vector<ScoredRowPair>> candidates;
  for (const auto& scene : scenes) {
    candidates.push_back(GcnCandidatePairs(model, scene, num_threads));
  }
  float best_threshold = model.info.threshold;
  double best_f = -1;
  // Steps of 0.05, refined towards both ends: a model's scores on an
  // unfamiliar collection can crowd near 0 or 1.
  std::vector<float> grid = {0.01f, 0.02f};
  for (int step = 1; step <= 19; ++step) grid.push_back(0.05f * step);
  for (float threshold : {0.97f, 0.98f, 0.99f, 0.995f, 0.999f}) {
    grid.push_back(threshold);
  }
  for (const float threshold : grid) {
    double sum_f = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
      sum_f +=
          ScorePairSet(PairsAtThreshold(candidates[s], threshold), scenes[s])
              .F();
    }
    const double mean_f = sum_f / scenes.size();
    if (mean_f >= best_f) {
      best_f = mean_f;
      best_threshold = threshold;
    }
  }
  return best_threshold;
}

std::vector<std::pair<int, int>> GcnRetrievedPairs(
    const GcnModel& model, const GcnTrainingScene& scene, int num_threads) {
  return PairsAtThreshold(GcnCandidatePairs(model, scene, num_threads),
                          model.info.threshold);
}

}  // namespace colmap_gcn

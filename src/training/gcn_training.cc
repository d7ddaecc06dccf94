#include "training/gcn_training.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <set>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "pairing/gcn_pair_generator.h"
#include "pairing/knn_pairing.h"
#include "retrieval/embedding_cache.h"
#include "scene/database.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/string.h"

namespace colmap_gcn {
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
  CHECK_OPTION(embedding,
               EmbeddingUsesVlad(embedding) || EmbeddingUsesCnn(embedding),
               "be vlad, onnx or vlad+onnx");
  vlad.Check();
  cnn.Check();
  if (EmbeddingUsesCnn(embedding)) {
    CHECK_OPTION(cnn.onnx_path,
                 !cnn.onnx_path.empty(),
                 "name the ONNX network when the embedding is " +
                     EnumName(ComputedEmbeddingTypeNames(), embedding));
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

namespace {

// Every database of the scenes once, in order, whether a scene or a
// collection's part.
std::vector<LabelledScene> SceneDatabases(
    const std::vector<LabelledScene>& scenes) {
  std::vector<LabelledScene> databases;
  std::set<std::string> seen;
  for (const auto& scene : scenes) {
    for (const auto& part : scene.parts.empty()
                                ? std::vector<LabelledScene>{scene}
                                : scene.parts) {
      if (seen.insert(part.database_path).second) databases.push_back(part);
    }
  }
  return databases;
}

// The embedding the model stores, trained on the training databases.
struct TrainedEmbedding {
  bool use_vlad = false;
  bool use_cnn = false;
  VladEmbedding vlad;
  CnnEmbeddingModel cnn_model;
  GcnEmbeddingConfig config;
};

TrainedEmbedding TrainEmbedding(
    const std::vector<LabelledScene>& training_scenes,
    const GcnTrainingPipelineOptions& options) {
  const std::vector<LabelledScene> databases = SceneDatabases(training_scenes);
  TrainedEmbedding trained;
  trained.use_vlad = EmbeddingUsesVlad(options.embedding);
  trained.use_cnn = EmbeddingUsesCnn(options.embedding);
  if (trained.use_vlad) {
    std::vector<std::string> database_paths;
    for (const auto& part : databases) {
      database_paths.push_back(part.database_path);
    }
    LOG(INFO) << "training the VLAD embedding on " << database_paths.size()
              << " databases";
    trained.vlad = TrainVladEmbedding(database_paths, options.vlad);
  }
  if (trained.use_cnn) {
    // Raw descriptors of every training database (cached, so embedding the
    // scenes afterwards reuses them), then the PCA on them.
    const CnnNetwork network(options.cnn);
    std::vector<FloatMatrix> collections;
    for (const auto& part : databases) {
      LOG(INFO) << "CNN descriptors of " << part.name;
      std::vector<image_t> image_ids;
      collections.push_back(
          ComputeDatabaseCnnDescriptors(Database(part.database_path),
                                        network,
                                        options.images.ImagePath(part),
                                        options.images.CnnCachePath(part),
                                        &image_ids));
    }
    trained.cnn_model = TrainCnnEmbeddingModel(network, collections);
    const CnnEmbeddingModel& cnn = trained.cnn_model;
    LOG(INFO) << "CNN embedding " << cnn.network_name << " (checksum "
              << FormatChecksum(cnn.network_checksum)
              << "): " << cnn.descriptor_dim << " -> " << cnn.OutputDim()
              << "-D";
  }
  trained.config =
      MakeEmbeddingConfig(trained.use_vlad ? &trained.vlad : nullptr,
                          trained.use_cnn ? &trained.cnn_model : nullptr);
  return trained;
}

// The scenes embedded with the model's embedding and labelled.
std::vector<GcnTrainingScene> MakeTrainingScenes(
    const std::vector<LabelledScene>& scenes,
    const ModelEmbedder& embedder,
    const GcnTrainingPipelineOptions& options) {
  std::vector<GcnTrainingScene> made;
  for (const auto& scene : scenes) {
    made.push_back(
        MakeTrainingScene(scene, embedder, options.images, options.labels));
    LOG(INFO) << "scene " << scene.name << ": " << made.back().embeddings.rows()
              << " images, " << made.back().positive_pairs.size()
              << " matchable pairs";
  }
  return made;
}

// The decision threshold stored in the model: options.threshold, or when
// negative the one maximising F on held-out data when there is some (on
// the training scenes the network's scores are optimistic).
float ChooseThreshold(const GcnModel& model,
                      const std::vector<GcnTrainingScene>& train,
                      const std::vector<GcnTrainingScene>& validation,
                      const GcnTrainingPipelineOptions& options) {
  if (options.threshold >= 0) return static_cast<float>(options.threshold);
  const std::vector<GcnTrainingScene>& selection =
      validation.empty() ? train : validation;
  const float threshold =
      SelectGcnThreshold(model, selection, options.training.num_threads);
  LOG(INFO) << "decision threshold " << std::to_string(threshold)
            << " (max mean F on the "
            << (validation.empty() ? "training" : "validation") << " scenes)";
  return threshold;
}

std::string PipelineNotes(const std::vector<LabelledScene>& training_scenes,
                          const std::vector<LabelledScene>& validation_scenes,
                          const TrainedEmbedding& embedding,
                          const GcnTrainingPipelineOptions& options,
                          float threshold,
                          uint32_t seed) {
  std::ostringstream notes;
  notes << "trained on";
  for (const auto& scene : training_scenes) notes << " " << scene.name;
  if (!validation_scenes.empty()) {
    notes << "; validated on";
    for (const auto& scene : validation_scenes) notes << " " << scene.name;
  }
  if (embedding.use_vlad) {
    notes << "; VLAD " << embedding.vlad.NumWords() << " words -> "
          << embedding.vlad.OutputDim() << "-D";
  }
  if (embedding.use_cnn) {
    const CnnEmbeddingModel& cnn = embedding.cnn_model;
    notes << "; CNN " << cnn.network_name << " (checksum "
          << FormatChecksum(cnn.network_checksum) << ", "
          << cnn.options.max_image_size << " px, GeM p " << cnn.options.gem_p
          << (cnn.options.center ? ", centred" : "") << ") -> "
          << cnn.OutputDim() << "-D";
  }
  notes << "; tau_MO " << options.labels.min_overlap << ", tau_CT "
        << options.labels.min_common_track_ratio << "; threshold " << threshold
        << "; seed " << seed;
  return notes.str();
}

}  // namespace

GcnModel TrainGcnModel(const std::vector<LabelledScene>& training_scenes,
                       const std::vector<LabelledScene>& validation_scenes,
                       const GcnTrainingPipelineOptions& options) {
  options.Check();
  const TrainedEmbedding embedding = TrainEmbedding(training_scenes, options);
  ModelEmbeddingOptions embedder_options;
  embedder_options.embedding.onnx_path = options.cnn.onnx_path;
  embedder_options.onnx_flag = "--GcnTraining.onnx_path";
  embedder_options.embedding.onnx_batch_size = options.cnn.batch_size;
  embedder_options.num_threads = options.training.num_threads;
  embedder_options.progress_every = options.cnn.progress_every;
  embedder_options.use_vlad_cache = false;
  const ModelEmbedder embedder(embedding.config, embedder_options);
  const std::vector<GcnTrainingScene> train =
      MakeTrainingScenes(training_scenes, embedder, options);
  const std::vector<GcnTrainingScene> validation =
      MakeTrainingScenes(validation_scenes, embedder, options);

  GcnTrainingOptions training = options.training;
  // A fixed threshold is also the one the epoch statistics use.
  if (options.threshold > 0) {
    training.threshold = static_cast<float>(options.threshold);
  }
  training.tau_mo = static_cast<float>(options.labels.min_overlap);
  training.tau_ct = static_cast<float>(options.labels.min_common_track_ratio);
  GcnTrainer trainer(training);
  GcnModel model = trainer.Train(train, validation);
  model.embedding = embedding.config;
  model.info.threshold = ChooseThreshold(model, train, validation, options);
  model.info.notes = PipelineNotes(training_scenes,
                                   validation_scenes,
                                   embedding,
                                   options,
                                   model.info.threshold,
                                   training.seed);
  return model;
}

}  // namespace colmap_gcn

#include "pairing/gcn_model_pairing.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "gcn/model_file.h"
#include "retrieval/embedding_cache.h"
#include "util/error.h"
#include "util/file.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

void GcnModelPairingOptions::Check() const {
  CHECK_OPTION_UNSET_OR_GE(k1, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_GE(k2, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_GE(u, -1, "the model's value", 1);
  CHECK_OPTION_UNSET_OR_RANGE(threshold, -1, "the model's value", 0.0, 1.0);
  CHECK_OPTION_GE(min_pairs_per_image, 0);
  CHECK_OPTION_NUM_THREADS(num_threads);
  embedding.Check();
}

std::string DefaultGcnModelPath() {
  const char* env = std::getenv("COLMAP_GCN_MODEL");
  if (env != nullptr && *env != '\0') {
    return env;
  }
  std::error_code ec;
  const std::filesystem::path exe =
      std::filesystem::canonical("/proc/self/exe", ec);
  const std::string kName = "default.gcnmodel";
  if (!ec) {
    const std::string installed =
        (exe.parent_path() / COLMAP_GCN_DATA_FROM_FRONTEND / kName)
            .lexically_normal()
            .string();
    if (ExistsFile(installed)) return installed;
  }
  const std::string source_tree =
      JoinPaths(COLMAP_GCN_SOURCE_DIR, "colmap_gcn/models/" + kName);
  return ExistsFile(source_tree) ? source_tree : "";
}

EmbeddingMatrix ComputeModelEmbeddings(const GcnModel& model,
                                       const Database& database,
                                       const ModelEmbeddingOptions& options,
                                       const std::string& image_path,
                                       std::vector<image_t>* image_ids) {
  const ModelEmbedder embedder(model.embedding, options);
  const EmbeddingMatrix embeddings = embedder.Finalize(embedder.EmbedDatabase(
      database, image_path, DefaultCnnCachePath(database.Path()), image_ids));
  model.CheckEmbeddingDimension(static_cast<int>(embeddings.cols()));
  return embeddings;
}

namespace {

// The GCN generator as gcn_matcher reports it: with the warning on a
// model that kept every candidate.
class GcnModelPairGenerator : public GcnPairGenerator {
 public:
  GcnModelPairGenerator(const GcnPairingOptions& options,
                        const std::vector<image_t>& image_ids,
                        const EmbeddingMatrix& embeddings,
                        const GcnModel& model,
                        const bool threshold_from_flag)
      : GcnPairGenerator(options, image_ids, embeddings, model),
        threshold_from_flag_(threshold_from_flag) {}

  std::string Warning() const override {
    return GcnKeptEveryCandidateWarning(
        Stats(), Options().k1, Options().threshold, threshold_from_flag_);
  }

 private:
  bool threshold_from_flag_;
};

}  // namespace

namespace {

std::unique_ptr<GcnPairGenerator> CreateGcnPairGenerator(
    const GcnModelPairingOptions& options,
    const Database& database,
    const bool every_candidate) {
  const std::string model_path =
      options.model_path.empty() ? DefaultGcnModelPath() : options.model_path;
  if (model_path.empty()) {
    ThrowError(
        "no GCN model: pass --GcnMatching.model_path (train one with colmap "
        "gcn_train) or choose another --GcnMatching.pairing");
  }
  const GcnModel model = ReadGcnModel(model_path);
  LOG(INFO) << "GCN model " << model_path;
  GcnPairingOptions pairing = GcnPairingOptionsFromModel(model);
  if (options.k1 > 0) pairing.k1 = options.k1;
  if (options.k2 > 0) pairing.k2 = options.k2;
  if (options.u > 0) pairing.u = options.u;
  if (options.threshold >= 0) pairing.threshold = options.threshold;
  pairing.min_pairs_per_image = options.min_pairs_per_image;
  pairing.num_threads = options.num_threads;
  if (every_candidate) pairing = EveryCandidate(pairing);
  ModelEmbeddingOptions embedding;
  embedding.embedding = options.embedding;
  embedding.num_threads = options.num_threads;
  embedding.use_vlad_cache = options.use_vlad_cache;
  std::vector<image_t> image_ids;
  const EmbeddingMatrix embeddings = ComputeModelEmbeddings(
      model, database, embedding, options.embedding.image_path, &image_ids);
  return std::make_unique<GcnModelPairGenerator>(
      pairing, image_ids, embeddings, model, options.threshold >= 0);
}

}  // namespace

std::unique_ptr<GcnPairGenerator> CreateGcnPairGenerator(
    const GcnModelPairingOptions& options, const Database& database) {
  return CreateGcnPairGenerator(options, database, /*every_candidate=*/false);
}

std::vector<ScoredImagePair> ScoreEveryGcnCandidate(
    const GcnModelPairingOptions& options, const Database& database) {
  return CreateGcnPairGenerator(options, database, /*every_candidate=*/true)
      ->ScoredPairs();
}

std::string GcnKeptEveryCandidateWarning(const GcnPairingStats& stats,
                                         const int k1,
                                         const double threshold,
                                         const bool threshold_from_flag) {
  if (stats.num_candidates == 0 ||
      stats.num_above_threshold < stats.num_candidates) {
    return "";
  }
  std::ostringstream threshold_text;
  threshold_text << threshold;
  const std::string kept = "all " + std::to_string(stats.num_candidates) +
                           " candidate pairs scored above ";
  const std::string chose =
      ": the GCN chose nothing beyond each image's k1 = " + std::to_string(k1) +
      " nearest neighbours; ";
  if (threshold_from_flag) {
    return kept + "--GcnMatching.threshold " + threshold_text.str() + chose +
           "a higher --GcnMatching.threshold keeps fewer (docs/model_card.md "
           "lists what to try)";
  }
  return kept + "the model's threshold " + threshold_text.str() + chose +
         "the model is likely not calibrated for these images "
         "(docs/model_card.md lists what to try)";
}

PairGeneratorSpec<GcnModelPairingOptions> GcnModelPairGeneratorSpec() {
  PairGeneratorSpec<GcnModelPairingOptions> spec;
  spec.name = "gcn";
  spec.add_options = [](OptionManager* manager,
                        GcnModelPairingOptions* options) {
    manager->AddDefaultOption(
        "GcnMatching.model_path",
        &options->model_path,
        "GCN model file (pairing=gcn); empty: default model");
    manager->AddDefaultOption("GcnMatching.k1",
                              &options->k1,
                              "1-hop neighbours per query; -1: model's value");
    manager->AddDefaultOption("GcnMatching.k2",
                              &options->k2,
                              "2-hop neighbours per 1-hop node; -1: model's");
    manager->AddDefaultOption("GcnMatching.u",
                              &options->u,
                              "neighbours that make QES edges; -1: model's");
    manager->AddDefaultOption(
        "GcnMatching.threshold",
        &options->threshold,
        "GCN score to retrieve a pair; -1: model's (0.5)");
    manager->AddDefaultOption("GcnMatching.min_pairs_per_image",
                              &options->min_pairs_per_image,
                              "best-scoring pairs every image keeps");
    AddEmbeddingOptions(manager, &options->embedding);
    manager->AddDefaultOption("GcnMatching.num_threads",
                              &options->num_threads,
                              "threads for embedding and kNN (-1: all cores)");
  };
  spec.create = [](const GcnModelPairingOptions& options,
                   const PairGeneratorContext& context)
      -> std::unique_ptr<PairGenerator> {
    return CreateGcnPairGenerator(options, context.database);
  };
  return spec;
}

}  // namespace colmap_gcn

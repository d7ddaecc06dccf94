#include "controllers/gcn_model_pairing.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "gcn/model_file.h"
#include "retrieval/descriptor_import.h"
#include "retrieval/embedding_cache.h"
#include "retrieval/vlad.h"
#include "util/error.h"
#include "util/file.h"
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
        (exe.parent_path().parent_path() / "share" / "colmap-gcn" / kName)
            .string();
    if (ExistsFile(installed)) return installed;
  }
  const std::string source_tree =
      JoinPaths(COLMAP_GCN_SOURCE_DIR, "colmap_gcn/models/" + kName);
  return ExistsFile(source_tree) ? source_tree : "";
}

EmbeddingMatrix ComputeModelEmbeddings(const GcnModel& model,
                                       const Database& database,
                                       const std::string& descriptor_path,
                                       int num_threads,
                                       std::vector<image_t>* image_ids) {
  const GcnEmbeddingConfig& config = model.embedding;
  EmbeddingMatrix embeddings;
  if (config.type == "vlad") {
    if (!descriptor_path.empty()) {
      ThrowError(
          "the GCN model was trained on its own VLAD embedding; imported "
          "descriptors (--GcnMatching.descriptor_path) need a model trained "
          "on them");
    }
    const VladEmbedding vlad =
        VladEmbedding::Deserialize(config.blob, "the GCN model's embedding");
    embeddings =
        ComputeDatabaseEmbeddings(database,
                                  vlad,
                                  image_ids,
                                  DefaultEmbeddingCachePath(database.Path()),
                                  num_threads);
  } else if (StringStartsWith(config.type, "imported")) {
    if (descriptor_path.empty()) {
      ThrowError("the GCN model was trained on imported descriptors (",
                 config.type,
                 "); pass them with --GcnMatching.descriptor_path");
    }
    embeddings =
        MatchDescriptorsToImages(ReadGlobalDescriptors(descriptor_path),
                                 database.ReadAllImages(),
                                 image_ids);
  } else {
    ThrowError(
        "the GCN model has an unknown embedding type \"", config.type, "\"");
  }
  model.CheckEmbeddingDimension(static_cast<int>(embeddings.cols()));
  return embeddings;
}

namespace {

// The GCN generator as gcn_matcher reports it: with the warning on a
// model that kept every candidate.
class GcnModelPairGenerator : public GcnPairGenerator {
 public:
  using GcnPairGenerator::GcnPairGenerator;

  std::string Warning() const override {
    return GcnKeptEveryCandidateWarning(Stats(), Options().k1);
  }
};

}  // namespace

std::unique_ptr<GcnPairGenerator> CreateGcnPairGenerator(
    const GcnModelPairingOptions& options, const Database& database) {
  const std::string model_path =
      options.model_path.empty() ? DefaultGcnModelPath() : options.model_path;
  if (model_path.empty()) {
    ThrowError(
        "no GCN model: pass --GcnMatching.model_path (train one with colmap "
        "gcn_train) or choose another --GcnMatching.pairing");
  }
  const GcnModel model = ReadGcnModel(model_path);
  GcnPairingOptions pairing = GcnPairingOptionsFromModel(model);
  if (options.k1 > 0) pairing.k1 = options.k1;
  if (options.k2 > 0) pairing.k2 = options.k2;
  if (options.u > 0) pairing.u = options.u;
  if (options.threshold >= 0) pairing.threshold = options.threshold;
  pairing.min_pairs_per_image = options.min_pairs_per_image;
  pairing.num_threads = options.num_threads;
  std::vector<image_t> image_ids;
  const EmbeddingMatrix embeddings =
      ComputeModelEmbeddings(model,
                             database,
                             options.descriptor_path,
                             options.num_threads,
                             &image_ids);
  return std::make_unique<GcnModelPairGenerator>(
      pairing, image_ids, embeddings, model);
}

std::string GcnKeptEveryCandidateWarning(const GcnPairingStats& stats, int k1) {
  if (stats.num_candidates == 0 ||
      stats.num_above_threshold < stats.num_candidates) {
    return "";
  }
  return "gcn_matcher: warning: all " + std::to_string(stats.num_candidates) +
         " candidate pairs scored above the model's threshold: the GCN "
         "chose nothing beyond each image's k1 = " +
         std::to_string(k1) +
         " nearest neighbours; the model is likely not calibrated for "
         "these images (docs/model_card.md). On photos of several "
         "unrelated places try --GcnMatching.threshold 0.9; on scenes with "
         "duplicate objects or repeated structure use --GcnMatching.pairing "
         "knn --GcnMatching.k 5 or sequential_matcher.";
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
    manager->AddDefaultOption(
        "GcnMatching.descriptor_path",
        &options->descriptor_path,
        "imported global descriptors (.h5 | .npy | .txt)");
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

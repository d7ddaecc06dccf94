#include "controllers/gcn_model_pairing.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "gcn/model_file.h"
#include "retrieval/descriptor_import.h"
#include "retrieval/embedding_cache.h"
#include "retrieval/vlad.h"
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
  CHECK_OPTION(embedding,
               embedding.empty() || embedding == "vlad" ||
                   embedding == "onnx" || embedding == "vlad+onnx" ||
                   embedding == "imported",
               "be empty (the model's; knn: vlad) or one of vlad, onnx, "
               "vlad+onnx, imported");
  onnx.Check();
  CHECK_OPTION_GE(onnx_batch_size, 1);
  if (embedding == "onnx" || embedding == "vlad+onnx") {
    CHECK_OPTION(
        onnx_path,
        !onnx_path.empty(),
        "name the ONNX network when --GcnMatching.embedding is " + embedding);
    CHECK_OPTION(image_path,
                 !image_path.empty(),
                 "name the image folder (the one given to feature_extractor) "
                 "when --GcnMatching.embedding is " +
                     embedding);
  }
  if (embedding == "imported") {
    CHECK_OPTION(descriptor_path,
                 !descriptor_path.empty(),
                 "name the descriptor file when --GcnMatching.embedding is "
                 "imported");
  }
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

namespace {

const char kConcatenatedMagic[8] = {'C', 'G', 'C', 'N', 'V', '+', 'O', 'N'};

void SplitConcatenatedBlob(const std::string& blob,
                           std::string* vlad,
                           std::string* cnn) {
  auto fail = [] {
    ThrowError("the GCN model's vlad+onnx embedding is malformed");
  };
  if (blob.size() < 8 + 16 || std::memcmp(blob.data(), kConcatenatedMagic, 8)) {
    fail();
  }
  size_t pos = 8;
  for (std::string* part : {vlad, cnn}) {
    uint64_t size;
    if (blob.size() - pos < 8) fail();
    std::memcpy(&size, blob.data() + pos, 8);
    pos += 8;
    if (size > blob.size() - pos) fail();
    *part = blob.substr(pos, size);
    pos += size;
  }
  if (pos != blob.size()) fail();
}

}  // namespace

GcnEmbeddingConfig MakeEmbeddingConfig(const VladEmbedding* vlad,
                                       const CnnEmbeddingModel* cnn) {
  THROW_CHECK(vlad != nullptr || cnn != nullptr);
  GcnEmbeddingConfig config;
  if (cnn == nullptr) {
    config.type = "vlad";
    config.dim = vlad->OutputDim();
    config.blob = vlad->Serialize();
  } else if (vlad == nullptr) {
    config.type = "onnx";
    config.dim = cnn->OutputDim();
    config.blob = cnn->Serialize();
  } else {
    config.type = "vlad+onnx";
    config.dim = vlad->OutputDim() + cnn->OutputDim();
    config.blob.assign(kConcatenatedMagic, 8);
    for (const std::string& part : {vlad->Serialize(), cnn->Serialize()}) {
      const uint64_t size = part.size();
      config.blob.append(reinterpret_cast<const char*>(&size), 8);
      config.blob += part;
    }
  }
  return config;
}

ModelEmbedder::ModelEmbedder(const GcnEmbeddingConfig& config,
                             const ModelEmbeddingOptions& options)
    : type_(config.type), options_(options) {
  const bool imported = StringStartsWith(type_, "imported");
  if (type_ != "vlad" && type_ != "onnx" && type_ != "vlad+onnx" && !imported) {
    ThrowError("the GCN model has an unknown embedding type \"", type_, "\"");
  }
  if (!options.embedding.empty() &&
      options.embedding != (imported ? "imported" : type_)) {
    ThrowError("the GCN model embeds with ",
               type_,
               " but --GcnMatching.embedding is ",
               options.embedding,
               "; train a model on it or leave the flag empty");
  }
  if (imported) {
    if (options.descriptor_path.empty()) {
      ThrowError("the GCN model was trained on imported descriptors (",
                 type_,
                 "); pass them with --GcnMatching.descriptor_path");
    }
    return;
  }
  if (!options.descriptor_path.empty()) {
    ThrowError("the GCN model was trained on its own ",
               type_,
               " embedding; imported descriptors "
               "(--GcnMatching.descriptor_path) need a model trained on them");
  }
  std::string vlad_blob = config.blob;
  std::string cnn_blob = config.blob;
  if (type_ == "vlad+onnx") {
    SplitConcatenatedBlob(config.blob, &vlad_blob, &cnn_blob);
  }
  if (type_ != "onnx") {
    vlad_ = VladEmbedding::Deserialize(vlad_blob, "the GCN model's embedding");
  }
  if (type_ == "vlad") return;
  cnn_model_ =
      CnnEmbeddingModel::Deserialize(cnn_blob, "the GCN model's embedding");
  if (options.onnx_path.empty()) {
    ThrowError("the GCN model embeds images with the ONNX network ",
               cnn_model_.network_name,
               " (checksum ",
               FormatChecksum(cnn_model_.network_checksum),
               "); pass it with ",
               options.onnx_flag);
  }
  options.onnx.CheckAgainst(cnn_model_.options, "--GcnMatching.onnx_");
  CnnEmbeddingOptions cnn = cnn_model_.options;
  cnn.onnx_path = options.onnx_path;
  cnn.batch_size = options.onnx_batch_size;
  cnn.num_threads = options.num_threads;
  cnn.progress_every = options.progress_every;
  network_ = std::make_unique<CnnNetwork>(cnn);
  cnn_model_.CheckNetwork(*network_, options.onnx_flag);
}

ModelEmbedder::~ModelEmbedder() = default;

EmbeddingMatrix ModelEmbedder::EmbedDatabase(
    const Database& database,
    const std::string& image_path,
    const std::string& cnn_cache_path,
    std::vector<image_t>* image_ids) const {
  if (StringStartsWith(type_, "imported")) {
    return MatchDescriptorsToImages(
        ReadGlobalDescriptors(options_.descriptor_path),
        database.ReadAllImages(),
        image_ids);
  }
  EmbeddingMatrix vlad;
  if (type_ != "onnx") {
    vlad = ComputeDatabaseEmbeddings(
        database,
        vlad_,
        image_ids,
        options_.use_vlad_cache ? DefaultEmbeddingCachePath(database.Path())
                                : "",
        options_.num_threads);
    if (type_ == "vlad") return vlad;
  }
  const FloatMatrix raw = ComputeDatabaseCnnDescriptors(
      database, *network_, image_path, cnn_cache_path, image_ids);
  if (type_ == "onnx") return raw;
  EmbeddingMatrix both(raw.rows(), vlad.cols() + raw.cols());
  both << vlad, raw;
  return both;
}

EmbeddingMatrix ModelEmbedder::Finalize(const EmbeddingMatrix& rows) const {
  if (type_ == "onnx") return cnn_model_.Apply(rows);
  if (type_ != "vlad+onnx") return rows;
  const int vlad_dim = vlad_.OutputDim();
  return ConcatenateEmbeddings(
      rows.leftCols(vlad_dim),
      cnn_model_.Apply(rows.rightCols(rows.cols() - vlad_dim)));
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
  LOG(INFO) << "GCN model " << model_path;
  GcnPairingOptions pairing = GcnPairingOptionsFromModel(model);
  if (options.k1 > 0) pairing.k1 = options.k1;
  if (options.k2 > 0) pairing.k2 = options.k2;
  if (options.u > 0) pairing.u = options.u;
  if (options.threshold >= 0) pairing.threshold = options.threshold;
  pairing.min_pairs_per_image = options.min_pairs_per_image;
  pairing.num_threads = options.num_threads;
  ModelEmbeddingOptions embedding;
  embedding.embedding = options.embedding;
  embedding.descriptor_path = options.descriptor_path;
  embedding.onnx_path = options.onnx_path;
  embedding.onnx = options.onnx;
  embedding.onnx_batch_size = options.onnx_batch_size;
  embedding.num_threads = options.num_threads;
  embedding.use_vlad_cache = options.use_vlad_cache;
  std::vector<image_t> image_ids;
  const EmbeddingMatrix embeddings = ComputeModelEmbeddings(
      model, database, embedding, options.image_path, &image_ids);
  return std::make_unique<GcnModelPairGenerator>(
      pairing, image_ids, embeddings, model, options.threshold >= 0);
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
    manager->AddDefaultOption(
        "GcnMatching.descriptor_path",
        &options->descriptor_path,
        "imported global descriptors (.h5 | .npy | .txt)");
    manager->AddDefaultOption(
        "GcnMatching.embedding",
        &options->embedding,
        "vlad | onnx | vlad+onnx | imported; empty: the model's (gcn), vlad "
        "(knn)");
    manager->AddDefaultOption("GcnMatching.onnx_path",
                              &options->onnx_path,
                              "ONNX network for embedding=onnx (OpenCV DNN)");
    manager->AddDefaultOption(
        "GcnMatching.image_path",
        &options->image_path,
        "folder of the images (as given to feature_extractor); needed by "
        "onnx");
    AddCnnEmbeddingOverrideOptions(
        manager, "GcnMatching.onnx_", &options->onnx);
    manager->AddDefaultOption("GcnMatching.onnx_batch_size",
                              &options->onnx_batch_size,
                              "images per CNN forward pass");
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

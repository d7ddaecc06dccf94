#include "controllers/gcn_model_pairing.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "retrieval/descriptor_import.h"
#include "retrieval/embedding_cache.h"
#include "retrieval/vlad.h"
#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {

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

}  // namespace colmap_gcn

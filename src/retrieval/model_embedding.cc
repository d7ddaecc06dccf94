#include "retrieval/model_embedding.h"

#include <cstring>

#include "retrieval/descriptor_import.h"
#include "retrieval/embedding_cache.h"
#include "util/error.h"
#include "util/string.h"

namespace colmap_gcn {

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
    : type_(EmbeddingConfigType(config)), options_(options) {
  const EmbeddingOptions& asked = options.embedding;
  if (asked.type != EmbeddingType::kDefault && asked.type != type_) {
    ThrowError("the GCN model embeds with ",
               config.type,
               " but --GcnMatching.embedding is ",
               EnumName(EmbeddingTypeNames(), asked.type),
               "; train a model on it or leave the flag at default");
  }
  if (type_ == EmbeddingType::kImported) {
    if (asked.descriptor_path.empty()) {
      ThrowError("the GCN model was trained on imported descriptors (",
                 config.type,
                 "); pass them with --GcnMatching.descriptor_path");
    }
    return;
  }
  if (!asked.descriptor_path.empty()) {
    ThrowError("the GCN model was trained on its own ",
               config.type,
               " embedding; imported descriptors "
               "(--GcnMatching.descriptor_path) need a model trained on them");
  }
  std::string vlad_blob = config.blob;
  std::string cnn_blob = config.blob;
  if (type_ == EmbeddingType::kVladOnnx) {
    SplitConcatenatedBlob(config.blob, &vlad_blob, &cnn_blob);
  }
  if (EmbeddingUsesVlad(type_)) {
    vlad_ = VladEmbedding::Deserialize(vlad_blob, "the GCN model's embedding");
  }
  if (!EmbeddingUsesCnn(type_)) return;
  cnn_model_ =
      CnnEmbeddingModel::Deserialize(cnn_blob, "the GCN model's embedding");
  if (asked.onnx_path.empty()) {
    ThrowError("the GCN model embeds images with the ONNX network ",
               cnn_model_.network_name,
               " (checksum ",
               FormatChecksum(cnn_model_.network_checksum),
               "); pass it with ",
               options.onnx_flag);
  }
  asked.onnx.CheckAgainst(cnn_model_.options, "--GcnMatching.onnx_");
  CnnEmbeddingOptions cnn = cnn_model_.options;
  cnn.onnx_path = asked.onnx_path;
  cnn.batch_size = asked.onnx_batch_size;
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
  if (type_ == EmbeddingType::kImported) {
    return MatchDescriptorsToImages(
        ReadGlobalDescriptors(options_.embedding.descriptor_path),
        database.ReadAllImages(),
        image_ids);
  }
  EmbeddingMatrix vlad;
  if (EmbeddingUsesVlad(type_)) {
    vlad = ComputeDatabaseEmbeddings(
        database,
        vlad_,
        image_ids,
        options_.use_vlad_cache ? DefaultEmbeddingCachePath(database.Path())
                                : "",
        options_.num_threads);
    if (!EmbeddingUsesCnn(type_)) return vlad;
  }
  const FloatMatrix raw = ComputeDatabaseCnnDescriptors(
      database, *network_, image_path, cnn_cache_path, image_ids);
  if (type_ == EmbeddingType::kOnnx) return raw;
  EmbeddingMatrix both(raw.rows(), vlad.cols() + raw.cols());
  both << vlad, raw;
  return both;
}

EmbeddingMatrix ModelEmbedder::Finalize(const EmbeddingMatrix& rows) const {
  if (type_ == EmbeddingType::kOnnx) return cnn_model_.Apply(rows);
  if (type_ != EmbeddingType::kVladOnnx) return rows;
  const int vlad_dim = vlad_.OutputDim();
  return ConcatenateEmbeddings(
      rows.leftCols(vlad_dim),
      cnn_model_.Apply(rows.rightCols(rows.cols() - vlad_dim)));
}

}  // namespace colmap_gcn

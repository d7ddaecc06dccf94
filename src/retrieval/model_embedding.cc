#include "retrieval/model_embedding.h"

#include "util/error.h"

namespace colmap_gcn {

ModelEmbedder::ModelEmbedder(const GcnEmbeddingConfig& config,
                             const ModelEmbeddingOptions& options)
    : type_(EmbeddingConfigType(config)) {
  const EmbeddingOptions& asked = options.embedding;
  if (asked.type != EmbeddingType::kDefault && asked.type != type_) {
    ThrowError("the GCN model embeds with ",
               config.type,
               " but --GcnMatching.embedding is ",
               EnumName(EmbeddingTypeNames(), asked.type),
               "; train a model on it or leave the flag at default");
  }
  if (type_ != EmbeddingType::kImported && !asked.descriptor_path.empty()) {
    ThrowError("the GCN model was trained on its own ",
               config.type,
               " embedding; imported descriptors "
               "(--GcnMatching.descriptor_path) need a model trained on them");
  }
  embedding_ = GetEmbeddingSpec(type_).load(config, options);
}

ModelEmbedder::~ModelEmbedder() = default;

EmbeddingMatrix ModelEmbedder::EmbedDatabase(
    const Database& database,
    const std::string& image_path,
    const std::string& cnn_cache_path,
    std::vector<image_t>* image_ids) const {
  return embedding_->EmbedDatabase(
      database, image_path, cnn_cache_path, image_ids);
}

EmbeddingMatrix ModelEmbedder::Finalize(const EmbeddingMatrix& rows) const {
  return embedding_->Finalize(rows);
}

}  // namespace colmap_gcn

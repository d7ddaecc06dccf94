#pragma once

#include <memory>
#include <string>
#include <vector>

#include "retrieval/cnn_embedding.h"
#include "retrieval/embedding.h"
#include "retrieval/embedding_spec.h"
#include "retrieval/vlad.h"
#include "scene/database.h"

namespace colmap_gcn {

// How a model's embedding runs on a database: the user's embedding flags
// and what the caller decides.
struct ModelEmbeddingOptions {
  // The embedding asked for (default: the model's; others must be it), the
  // imported descriptors of models trained on them, the ONNX network of
  // onnx / vlad+onnx models (checked against the checksum in the model) and
  // its preprocessing as set by the user (unset: the model's; set values
  // must match); image_path is not used here (EmbedDatabase takes it).
  EmbeddingOptions embedding;

  // The flag that named onnx_path, for messages.
  std::string onnx_flag = "--GcnMatching.onnx_path";

  // Threads; -1 uses all cores. Results do not depend on it.
  int num_threads = -1;

  // A progress line every this many CNN images; 0 is silent.
  int progress_every = 50;

  // Keep VLAD embeddings in "<database>.gcn-embedding.bin" (CNN caches are
  // named per call).
  bool use_vlad_cache = true;
};

// A model's embedding (GcnEmbeddingConfig) loaded once through its
// EmbeddingSpec (VLAD codebook, or the ONNX network checked against the
// model's checksum), to embed one or more databases, with caches keyed
// (fingerprinted) on the features or image files and the model. Throws Error
// for an unknown type, a type other than the one asked for, a missing onnx_path
// / descriptor_path, another network or configuration.
class ModelEmbedder {
 public:
  ModelEmbedder(const GcnEmbeddingConfig& config,
                const ModelEmbeddingOptions& options);
  ~ModelEmbedder();

  EmbeddingType Type() const { return type_; }

  // One row per database image (ascending id, in *image_ids) before the
  // collection step: VLAD / imported rows as they are, CNN rows raw.
  // image_path is the folder of the database's images (CNN types);
  // cnn_cache_path "" disables the CNN cache.
  EmbeddingMatrix EmbedDatabase(const Database& database,
                                const std::string& image_path,
                                const std::string& cnn_cache_path,
                                std::vector<image_t>* image_ids) const;

  // The collection step on the rows of one collection (one database, or
  // several stacked): CNN centring and PCA, the VLAD ⊕ CNN concatenation.
  EmbeddingMatrix Finalize(const EmbeddingMatrix& rows) const;

 private:
  EmbeddingType type_;
  std::unique_ptr<DatabaseEmbedding> embedding_;
};

// The embedding config of a trained VLAD ("vlad"), CNN ("onnx") or both
// ("vlad+onnx": blob = magic + u64 length + VLAD bytes + u64 length + CNN
// bytes); defined beside the vlad+onnx reader in embedding_specs.cc.
GcnEmbeddingConfig MakeEmbeddingConfig(const VladEmbedding* vlad,
                                       const CnnEmbeddingModel* cnn);

}  // namespace colmap_gcn

#pragma once

#include <memory>
#include <string>
#include <vector>

#include "gcn/gcn_model.h"
#include "gcn/gcn_pair_generator.h"
#include "retrieval/cnn_embedding.h"
#include "retrieval/knn.h"
#include "retrieval/vlad.h"
#include "scene/database.h"

namespace colmap_gcn {

// The model `gcn_matcher` uses when none is given: $COLMAP_GCN_MODEL, else
// the one installed beside the front end (../share/colmap-gcn/), else the
// one in the source tree (colmap_gcn/models/default.gcnmodel). Empty if
// there is none.
std::string DefaultGcnModelPath();

// What embedding a model's images needs beyond the model file
// (--GcnMatching.*).
struct ModelEmbeddingOptions {
  // The embedding asked for: "" takes the model's; vlad | onnx | vlad+onnx
  // | imported must be the model's.
  std::string embedding = "";

  // Imported descriptors, for models trained on them.
  std::string descriptor_path = "";

  // The ONNX network of models of type onnx / vlad+onnx (checked against
  // the checksum in the model), its preprocessing as set by the user (unset:
  // the model's; set values must match), and its batch size.
  std::string onnx_path = "";
  CnnEmbeddingOverrides onnx;
  int onnx_batch_size = 1;

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

// The model's embedding, loaded once (VLAD codebook, or the ONNX network
// checked against the model's checksum), to embed one or more databases.
// Throws Error for an unknown type, a type other than the one asked for, a
// missing onnx_path / descriptor_path, another network or configuration.
class ModelEmbedder {
 public:
  ModelEmbedder(const GcnEmbeddingConfig& config,
                const ModelEmbeddingOptions& options);
  ~ModelEmbedder();

  const std::string& Type() const { return type_; }

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
  std::string type_;
  ModelEmbeddingOptions options_;
  VladEmbedding vlad_;
  CnnEmbeddingModel cnn_model_;
  std::unique_ptr<CnnNetwork> network_;
};

// The GcnModel::embedding of a trained VLAD ("vlad"), CNN ("onnx") or both
// ("vlad+onnx": blob = u64 length + VLAD bytes + u64 length + CNN bytes).
GcnEmbeddingConfig MakeEmbeddingConfig(const VladEmbedding* vlad,
                                       const CnnEmbeddingModel* cnn);

// The global descriptors the model was trained on, one row per database
// image (ascending image id, in *image_ids): the model's own VLAD embedding
// (cached beside the database, keyed on features and model), its CNN on the
// images in image_path (cached likewise, keyed on the image files and
// network), both, or, for a model trained on imported descriptors, those in
// options.descriptor_path. Throws Error on a dimension or type mismatch.
EmbeddingMatrix ComputeModelEmbeddings(const GcnModel& model,
                                       const Database& database,
                                       const ModelEmbeddingOptions& options,
                                       const std::string& image_path,
                                       std::vector<image_t>* image_ids);

}  // namespace colmap_gcn

#pragma once

#include <memory>
#include <string>
#include <vector>

#include "feature/pair_generator_spec.h"
#include "gcn/gcn_model.h"
#include "gcn/gcn_pair_generator.h"
#include "retrieval/cnn_embedding.h"
#include "retrieval/knn.h"
#include "retrieval/vlad.h"
#include "scene/database.h"

namespace colmap_gcn {

// The GCN generator of `gcn_matcher` (--GcnMatching.pairing gcn): a model
// file and its QES settings, each -1 taking the model's recommendation.
struct GcnModelPairingOptions {
  // GCN model file (`colmap gcn_train`); empty: DefaultGcnModelPath().
  std::string model_path = "";

  // Query Enclosing Subgraph sizes (>= 1) and decision threshold (in
  // [0, 1]); -1 uses the model's recommendation.
  int k1 = -1;
  int k2 = -1;
  int u = -1;
  double threshold = -1;

  // Every image keeps at least this many pairs, its best-scoring ones, even
  // when none clears the threshold.
  int min_pairs_per_image = 2;

  // Imported global descriptors (.h5 / .npy / .txt), for a model trained on
  // them; empty: the model's own embedding.
  std::string descriptor_path = "";

  // The embedding asked for: "" takes the model's; vlad | onnx | vlad+onnx
  // | imported must be the model's.
  std::string embedding = "";

  // For models of type onnx / vlad+onnx: the ONNX network (checked against
  // the checksum in the model), run by OpenCV DNN on the image files in
  // image_path (the folder given to feature_extractor); its preprocessing
  // as set by the user (-1: the model's; set values must match); images per
  // forward pass.
  std::string onnx_path = "";
  std::string image_path = "";
  CnnEmbeddingOverrides onnx;
  int onnx_batch_size = 1;

  // Threads for embedding, kNN and inference; -1 uses all cores.
  int num_threads = -1;

  // Keep the VLAD embedding in "<database>.gcn-embedding.bin" (no flag;
  // off for tools that read databases they must not write beside).
  bool use_vlad_cache = true;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// The model `gcn_matcher` uses when none is given: $COLMAP_GCN_MODEL, else
// the one installed with the front end (<prefix>/share/colmap-gcn/ for
// <prefix>/lib/colmap-gcn/colmap), else the one in the source tree
// (colmap_gcn/models/default.gcnmodel). Empty if there is none.
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

// The GCN generator: the model (or the default one), its embedding of the
// database, and the QES settings (model's recommendation unless set).
std::unique_ptr<GcnPairGenerator> CreateGcnPairGenerator(
    const GcnModelPairingOptions& options, const Database& database);

// A one-line warning when the GCN kept every candidate pair it scored: it
// then chose nothing beyond the k1 nearest neighbours, which is what a
// model does on images unlike its training scenes (all real photo sets
// for the default model, docs/model_card.md), and on scenes with
// duplicate structure it admits the pairs that fold models. "" otherwise.
// The threshold is named by where it came from: the model file, or
// --GcnMatching.threshold (threshold_from_flag).
std::string GcnKeptEveryCandidateWarning(const GcnPairingStats& stats,
                                         int k1,
                                         double threshold,
                                         bool threshold_from_flag);

// --GcnMatching.pairing gcn (--GcnMatching.model_path, k1, k2, u,
// threshold, min_pairs_per_image, descriptor_path, embedding, onnx_path,
// image_path, onnx_*, num_threads); its
// generator's Warning() is GcnKeptEveryCandidateWarning.
PairGeneratorSpec<GcnModelPairingOptions> GcnModelPairGeneratorSpec();

}  // namespace colmap_gcn

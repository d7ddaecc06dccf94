#pragma once

#include <memory>
#include <string>
#include <vector>

#include "gcn/gcn_model.h"
#include "pairing/gcn_pair_generator.h"
#include "pairing/pair_generator_spec.h"
#include "retrieval/knn.h"
#include "retrieval/model_embedding.h"
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

  // The embedding flags: default takes the model's embedding, others must
  // be it; imported descriptors for a model trained on them; for models of
  // type onnx / vlad+onnx the ONNX network (checked against the checksum in
  // the model), run by OpenCV DNN on the image files in image_path, and its
  // preprocessing as set by the user (-1: the model's; set values must
  // match).
  EmbeddingOptions embedding;

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

// Every candidate that generator scores (EveryCandidate: threshold and
// min_pairs_per_image ignored), with its score.
std::vector<ScoredImagePair> ScoreEveryGcnCandidate(
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
// threshold, min_pairs_per_image, the embedding flags (AddEmbeddingOptions),
// num_threads); its
// generator's Warning() is GcnKeptEveryCandidateWarning.
PairGeneratorSpec<GcnModelPairingOptions> GcnModelPairGeneratorSpec();

}  // namespace colmap_gcn

#pragma once

#include <memory>
#include <string>
#include <vector>

#include "feature/pair_generator_spec.h"
#include "gcn/gcn_model.h"
#include "gcn/gcn_pair_generator.h"
#include "retrieval/knn.h"
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
  // them; empty: the model's own VLAD.
  std::string descriptor_path = "";

  // Threads for embedding, kNN and inference; -1 uses all cores.
  int num_threads = -1;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// The model `gcn_matcher` uses when none is given: $COLMAP_GCN_MODEL, else
// the one installed beside the front end (../share/colmap-gcn/), else the
// one in the source tree (colmap_gcn/models/default.gcnmodel). Empty if
// there is none.
std::string DefaultGcnModelPath();

// The global descriptors the model was trained on, one row per database
// image (ascending image id, in *image_ids): the model's own VLAD embedding
// (cached beside the database, keyed on features and model), or, for a
// model trained on imported descriptors, those in descriptor_path. Throws
// Error on a dimension or type mismatch.
EmbeddingMatrix ComputeModelEmbeddings(const GcnModel& model,
                                       const Database& database,
                                       const std::string& descriptor_path,
                                       int num_threads,
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
std::string GcnKeptEveryCandidateWarning(const GcnPairingStats& stats, int k1);

// --GcnMatching.pairing gcn (--GcnMatching.model_path, k1, k2, u,
// threshold, min_pairs_per_image, descriptor_path, num_threads); its
// generator's Warning() is GcnKeptEveryCandidateWarning.
PairGeneratorSpec<GcnModelPairingOptions> GcnModelPairGeneratorSpec();

}  // namespace colmap_gcn

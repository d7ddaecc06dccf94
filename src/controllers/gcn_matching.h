#pragma once

#include <memory>
#include <string>
#include <vector>

#include "controllers/pair_matching.h"
#include "feature/pairing.h"
#include "gcn/gcn_pair_generator.h"
#include "retrieval/cnn_embedding.h"
#include "scene/database.h"

namespace colmap_gcn {

// How `gcn_matcher` chooses pairs: the options users set as --GcnMatching.*.
struct GcnMatchingOptions {
  // Pair generator: gcn | exhaustive | imported | knn | vocab_tree.
  std::string pairing = "gcn";

  // GCN model file (`colmap gcn_train`); empty: the default model
  // (pairing = gcn).
  std::string model_path = "";

  // Query Enclosing Subgraph sizes (>= 1) and decision threshold (in
  // [0, 1]) (pairing = gcn); -1 uses the model's recommendation.
  int k1 = -1;
  int k2 = -1;
  int u = -1;
  double threshold = -1;

  // Every image keeps at least this many GCN pairs, its best-scoring ones,
  // even when none clears the threshold (pairing = gcn).
  int min_pairs_per_image = 2;

  // Pairs file to import (pairing = imported).
  std::string match_list_path = "";

  // Neighbours retrieved per image (pairing = knn | vocab_tree).
  int k = 25;

  // Trained VLAD model (`colmap gcn_embedding_trainer`); empty: train on the
  // database itself (pairing = knn).
  std::string embedding_path = "";

  // Imported global descriptors, .h5 (hloc) / .npy / .txt, used instead of
  // VLAD (pairing = knn, or gcn with a model trained on them).
  std::string descriptor_path = "";

  // Embedding (pairing = gcn | knn): "" (gcn: the model's; knn: imported
  // with descriptor_path, else vlad) | vlad | onnx | vlad+onnx | imported.
  // onnx runs the ONNX network onnx_path (OpenCV DNN) on the image files in
  // image_path (the folder given to feature_extractor); onnx.* are its
  // input size, normalisation and GeM exponent (-1: the model's, or for knn
  // MobileNetV2's; docs/retrieval.md).
  std::string embedding = "";
  std::string onnx_path = "";
  std::string image_path = "";
  CnnEmbeddingOverrides onnx;
  int onnx_batch_size = 1;

  // Vocabulary tree; empty: build one from the database itself
  // (pairing = vocab_tree).
  std::string vocab_tree_path = "";

  // Threads for embedding and kNN; -1 uses all cores.
  int num_threads = -1;

  // Pairs per COLMAP matching run; each run commits, so an interrupted
  // matching loses at most one block.
  int block_size = 1225;

  // Where the chosen pairs are written; empty: "<database_path>.pairs.txt".
  std::string pairs_path = "";

  // Log of every COLMAP call with its full output; empty:
  // "<database_path>.colmap.log".
  std::string colmap_log_path = "";

  // Show all of COLMAP's output, not only progress.
  bool verbose = false;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// Throws Error when the folder that is to hold `path` (a log or pairs
// file) does not exist; "" passes.
void CheckOutputFolder(const std::string& path);

// The GCN generator: the model (or the default one), its embedding of the
// database, and the QES settings (model's recommendation unless set).
std::unique_ptr<GcnPairGenerator> CreateGcnPairGenerator(
    const GcnMatchingOptions& options, const Database& database);

// The factory behind --GcnMatching.pairing; throws Error on a bad choice.
std::unique_ptr<PairGenerator> CreatePairGenerator(
    const GcnMatchingOptions& options, const Database& database);

struct GcnMatchingReport {
  std::string pairing;
  size_t num_images = 0;
  double pairing_seconds = 0;  // choosing the pairs
  PairMatchingSummary matching;
};

// The whole `gcn_matcher` path: database -> pair generator -> pairs file ->
// COLMAP matches_importer -> statistics. colmap_args are the user's
// --SiftMatching.* options.
GcnMatchingReport RunGcnMatching(const std::string& database_path,
                                 const GcnMatchingOptions& options,
                                 const std::vector<std::string>& colmap_args);

// The short table users see.
void PrintGcnMatchingReport(const GcnMatchingReport& report);

// A one-line warning when the GCN kept every candidate pair it scored: it
// then chose nothing beyond the k1 nearest neighbours, which is what a
// model does on images unlike its training scenes (all real photo sets
// for the default model, docs/model_card.md), and on scenes with
// duplicate structure it admits the pairs that fold models. "" otherwise.
std::string GcnKeptEveryCandidateWarning(const GcnPairingStats& stats, int k1);

}  // namespace colmap_gcn

#pragma once

#include <memory>
#include <string>
#include <vector>

#include "controllers/gcn_model_pairing.h"
#include "controllers/pair_matching.h"
#include "controllers/vocab_tree_pairing.h"
#include "feature/pairing.h"
#include "gcn/gcn_pair_generator.h"
#include "retrieval/knn_pairing.h"
#include "scene/database.h"

namespace colmap_gcn {

// How `gcn_matcher` chooses and matches pairs: the options users set as
// --GcnMatching.* (flags in AddGcnMatchingOptions, exe/gcn_matcher.cc) and
// --SiftMatching.*. One sub-struct per pair generator; only the chosen
// generator's is used.
struct GcnMatchingOptions {
  // Pair generator: gcn | exhaustive | imported | knn | vocab_tree.
  std::string pairing = "gcn";

  GcnModelPairingOptions gcn;
  ExhaustiveMatchingOptions exhaustive;
  ImagePairsMatchingOptions imported;
  KnnPairingOptions knn;
  VocabTreePairingOptions vocab_tree;

  // Matching the chosen pairs with COLMAP.
  struct Matching {
    // Pairs per COLMAP matching run; each run commits, so an interrupted
    // matching loses at most one block.
    int block_size = 1225;

    // Where the chosen pairs are written; empty:
    // "<database_path>.pairs.txt".
    std::string pairs_path = "";

    // Log of every COLMAP call with its full output; empty:
    // "<database_path>.colmap.log".
    std::string colmap_log_path = "";

    // Show all of COLMAP's output, not only progress.
    bool verbose = false;

    void Check() const;
  } matching;

  // Passed to COLMAP's matches_importer unchanged: the user's
  // --SiftMatching.* arguments.
  std::vector<std::string> colmap_args;

  // Throws OptionError naming the first invalid field (of the chosen
  // generator and of matching).
  void Check() const;
};

// Throws Error when the folder that is to hold `path` (a log or pairs
// file) does not exist; "" passes.
void CheckOutputFolder(const std::string& path);

// The GCN generator: the model (or the default one), its embedding of the
// database, and the QES settings (model's recommendation unless set).
std::unique_ptr<GcnPairGenerator> CreateGcnPairGenerator(
    const GcnModelPairingOptions& options, const Database& database);

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
// COLMAP matches_importer -> statistics.
GcnMatchingReport RunGcnMatching(const std::string& database_path,
                                 const GcnMatchingOptions& options);

// The short table users see.
void PrintGcnMatchingReport(const GcnMatchingReport& report);

// A one-line warning when the GCN kept every candidate pair it scored: it
// then chose nothing beyond the k1 nearest neighbours, which is what a
// model does on images unlike its training scenes (all real photo sets
// for the default model, docs/model_card.md), and on scenes with
// duplicate structure it admits the pairs that fold models. "" otherwise.
std::string GcnKeptEveryCandidateWarning(const GcnPairingStats& stats, int k1);

}  // namespace colmap_gcn

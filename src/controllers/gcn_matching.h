#pragma once

#include <memory>
#include <string>
#include <vector>

#include "controllers/pair_matching.h"
#include "feature/pairing.h"
#include "scene/database.h"

namespace colmap_gcn {

// How `gcn_matcher` chooses pairs: the options users set as --GcnMatching.*.
struct GcnMatchingOptions {
  // Pair generator: exhaustive | imported | knn | vocab_tree.
  std::string pairing = "exhaustive";

  // Pairs file to import (pairing = imported).
  std::string match_list_path = "";

  // Neighbours retrieved per image (pairing = knn | vocab_tree).
  int k = 25;

  // Trained VLAD model (`colmap gcn_embedding_trainer`); empty: train on the
  // database itself (pairing = knn).
  std::string embedding_path = "";

  // Imported global descriptors, .h5 (hloc) / .npy / .txt, used instead of
  // VLAD (pairing = knn).
  std::string descriptor_path = "";

  // Vocabulary tree; empty: build one from the database itself
  // (pairing = vocab_tree).
  std::string vocab_tree_path = "";

  // Threads for embedding and kNN; -1 uses all cores.
  int num_threads = -1;

  // Where the chosen pairs are written; empty: "<database_path>.pairs.txt".
  std::string pairs_path = "";

  // Log of every COLMAP call with its full output; empty:
  // "<database_path>.colmap.log".
  std::string colmap_log_path = "";

  // Show all of COLMAP's output, not only progress.
  bool verbose = false;

  bool Check() const;
};

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

}  // namespace colmap_gcn

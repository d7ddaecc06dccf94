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
  // Pair generator: exhaustive | imported.
  std::string pairing = "exhaustive";

  // Pairs file to import (pairing = imported).
  std::string match_list_path = "";

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

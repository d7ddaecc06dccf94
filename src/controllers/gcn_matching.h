#pragma once

#include <memory>
#include <string>
#include <vector>

#include "controllers/pair_generators.h"
#include "controllers/pair_matching.h"
#include "disambiguation/pair_filter.h"
#include "pairing/pairing.h"
#include "scene/database.h"

namespace colmap_gcn {

// How `gcn_matcher` chooses and matches pairs: the options users set as
// --GcnMatching.* (AddGcnMatchingOptions, exe/gcn_matcher.cc) and
// --SiftMatching.*.
struct GcnMatchingOptions {
  // Every registered generator's options at their defaults.
  GcnMatchingOptions();

  // Pair generator, a name in PairGenerators(); default: kDefaultPairing
  // (adaptive).
  std::string pairing;

  // Each generator's own options, e.g. generators.Get<KnnPairingOptions>(
  // "knn"); only the chosen generator's are used.
  PairGeneratorOptions generators;

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

    // gcn_matcher writes a picture of the view graph next to the pairs file
    // (exe/gcn_matcher.h: ViewGraphFigurePath).
    bool write_figures = true;

    // COLMAP's --SiftMatching.min_num_inliers, read once here: passed to
    // its verification and used to count verified pairs (UM).
    int min_num_inliers = kDefaultMinNumInliers;

    void Check() const;
  } matching;

  // After matching, hide verified pairs of duplicate structure from COLMAP's
  // mapper (docs/lookalike.md); its min_num_inliers is matching's. On by
  // default (measured on ordinary scenes in docs/lookalike.md); false turns
  // it off.
  bool filter_lookalikes = true;
  PairFilterOptions lookalike_filter;

  // Passed to COLMAP's matches_importer unchanged: the user's other
  // --SiftMatching.* arguments.
  std::vector<std::string> colmap_args;

  // Throws OptionError naming the first invalid field (of the chosen
  // generator and of matching).
  void Check() const;
};

// Throws Error when the folder that is to hold `path` (a log or pairs
// file) does not exist; "" passes.
void CheckOutputFolder(const std::string& path);

// The generator --GcnMatching.pairing names, from PairGenerators(); throws
// Error on a bad choice or invalid options.
std::unique_ptr<PairGenerator> CreatePairGenerator(
    const GcnMatchingOptions& options, const Database& database);

struct GcnMatchingReport {
  std::string pairing;
  size_t num_images = 0;
  double pairing_seconds = 0;  // choosing the pairs
  PairMatchingSummary matching;
  bool filtered_lookalikes = false;
  size_t num_lookalike_pairs = 0;  // hidden by the look-alike filter
  double filter_seconds = 0;
};

// The whole `gcn_matcher` path: database -> pair generator -> pairs file ->
// COLMAP matches_importer -> statistics.
GcnMatchingReport RunGcnMatching(const std::string& database_path,
                                 const GcnMatchingOptions& options);

// The short table users see.
void PrintGcnMatchingReport(const GcnMatchingReport& report);

}  // namespace colmap_gcn

#pragma once

#include <string>
#include <vector>

#include "controllers/colmap_runner.h"
#include "disambiguation/pair_filter.h"
#include "pairing/pairing.h"
#include "scene/database.h"
#include "util/types.h"
#include "verification/pair_verification.h"

namespace colmap_gcn {

struct PairMatchingOptions {
  // Where the pairs file handed to COLMAP is written; empty: beside the
  // database as "<database_path>.pairs.txt".
  std::string pairs_path = "";

  // COLMAP's --SiftMatching.min_num_inliers: passed to its verification,
  // and the inliers a verified pair needs to count as useful (UM).
  int min_num_inliers = kDefaultMinNumInliers;

  // Optional scores parallel to the pairs (e.g. the GCN's), written as the
  // pairs file's third column, which COLMAP ignores.
  std::vector<float> scores;

  // Most pairs per COLMAP run. Each run commits its matches, so an
  // interrupted matching resumes having lost at most one block; COLMAP 3.8
  // batches its own database writes in blocks of 1225 pairs. Runs are
  // smaller (ProgressBlockSize) so that progress shows every 10 %.
  int block_size = 1225;

  // Forwarded verbatim to `colmap matches_importer` (the user's other
  // --SiftMatching.* options; never --SiftMatching.min_num_inliers).
  std::vector<std::string> colmap_args;

  // Generators that use verification (adaptive, graphmatch): each round,
  // the pairs the look-alike filter rejects (docs/lookalike.md) reach the
  // generator as unverified, so propagation never crosses them.
  bool lookalikes_unverified = false;
  PairFilterOptions lookalike_filter;

  // The features are matched here, exhaustively (MatchPairsExactly: the
  // same matches on every run, unlike COLMAP 3.8's approximate search), and
  // COLMAP verifies them (`matches_importer --match_type raw`). Generators
  // that use verification decide on a deterministic verification of those
  // matches (verification/pair_verification.h), not on COLMAP's, whose
  // RANSAC differs from run to run. Both follow the --SiftMatching.* values
  // in colmap_args (max_ratio, max_distance, cross_check; max_error,
  // confidence, max_num_trials, min_inlier_ratio), and min_num_inliers
  // above.
  ExactMatchingOptions matching;
  ExactVerificationOptions verification;

  void Check() const;
};

// What matching a pair set cost and bought, in the paper's terms.
struct PairMatchingSummary {
  size_t num_attempted_pairs = 0;  // TAM: distinct pairs in the set
  size_t num_already_matched = 0;  // of those, matched before this run
  size_t num_verified_pairs = 0;   // UM: of those, geometrically verified
  double matching_seconds = 0;     // wall time of COLMAP's matching
  std::string pairs_path;          // the pairs file that was written
  // Generators that use verification (MatchPairGenerator): blocks asked
  // for, and the time spent in the generator between them.
  size_t num_rounds = 0;
  double generator_seconds = 0;
  // Of generator_seconds: the deterministic verification of the rounds.
  double verification_seconds = 0;

  double UsefulRatio() const {
    return num_attempted_pairs == 0
               ? 0.0
               : static_cast<double>(num_verified_pairs) / num_attempted_pairs;
  }
};

// Pairs per matches_importer run for num_pairs pairs: a tenth of them, at
// least 100, at most max_block_size.
size_t ProgressBlockSize(size_t num_pairs, int max_block_size);

// Matches and verifies the pairs with COLMAP's own matcher
// (`matches_importer --match_type pairs`), in blocks of
// options.block_size. Pairs already verified in the database are skipped.
// The user's database is never left half-written: COLMAP works on a
// DatabaseWorkingCopy, which replaces the database atomically on success
// and is resumed after an interruption. Holds the database's lock
// (DatabaseLockPath) while it runs.
PairMatchingSummary MatchImagePairs(const ColmapRunner& colmap,
                                    const std::string& database_path,
                                    const std::vector<ImagePair>& pairs,
                                    const PairMatchingOptions& options);

// Matches what `generator` chooses, with MatchImagePairs' guarantees (one
// DatabaseWorkingCopy replacing the database atomically at the end, resumed
// after an interruption, the lock held throughout). A generator that does
// not use verification is drained with AllPairs() and matched by
// MatchImagePairs (its Scores() as the pairs file's third column); one that
// does is run as a loop: Next() block -> COLMAP matches the block's pairs
// that the working copy has no two_view_geometries row for -> Observe()
// gets every pair of the block with its row (no row: config 0, 0 inliers)
// -> until HasFinished(). After an interruption the same blocks come back
// and are answered from the working copy without matching, so the rounds
// are reconstructed from what the copy holds. The pairs file (all pairs
// attempted, with the generator's scores) is rewritten after every round.
// *pairs, if given, receives the attempted pairs in yield order.
// options.scores must be empty (they come from the generator).
PairMatchingSummary MatchPairGenerator(const ColmapRunner& colmap,
                                       const std::string& database_path,
                                       PairGenerator* generator,
                                       const PairMatchingOptions& options,
                                       std::vector<ImagePair>* pairs = nullptr);

}  // namespace colmap_gcn

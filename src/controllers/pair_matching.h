#pragma once

#include <string>
#include <vector>

#include "controllers/colmap_runner.h"
#include "util/types.h"

namespace colmap_gcn {

struct PairMatchingOptions {
  // Where the pairs file handed to COLMAP is written; empty: beside the
  // database as "<database_path>.pairs.txt".
  std::string pairs_path = "";

  // Minimum inliers for a verified pair to count as useful (UM). Taken from
  // --SiftMatching.min_num_inliers when that is among colmap_args.
  int min_num_inliers = 15;

  // Optional scores parallel to the pairs (e.g. the GCN's), written as the
  // pairs file's third column, which COLMAP ignores.
  std::vector<float> scores;

  // Forwarded verbatim to `colmap matches_importer` (the user's
  // --SiftMatching.* options).
  std::vector<std::string> colmap_args;

  bool Check() const;
};

// What matching a pair set cost and bought, in the paper's terms.
struct PairMatchingSummary {
  size_t num_attempted_pairs = 0;  // TAM: distinct pairs in the set
  size_t num_already_matched = 0;  // of those, matched before this run
  size_t num_verified_pairs = 0;   // UM: of those, geometrically verified
  double matching_seconds = 0;     // wall time of COLMAP's matching
  std::string pairs_path;          // the pairs file that was written

  double UsefulRatio() const {
    return num_attempted_pairs == 0
               ? 0.0
               : static_cast<double>(num_verified_pairs) / num_attempted_pairs;
  }
};

// Matches and verifies the pairs with COLMAP's own matcher
// (`matches_importer --match_type pairs`). Pairs already verified in the
// database are skipped, so an interrupted run resumes. The user's database
// is never left half-written: COLMAP works on a copy beside it
// ("<database>.gcn-partial"), which replaces the original atomically on
// success and is kept for resuming on failure.
PairMatchingSummary MatchImagePairs(const ColmapRunner& colmap,
                                    const std::string& database_path,
                                    const std::vector<ImagePair>& pairs,
                                    const PairMatchingOptions& options);

}  // namespace colmap_gcn

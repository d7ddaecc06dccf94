#pragma once

#include <string>
#include <vector>

#include "verification/exact_matching.h"
#include "verification/pair_verification.h"

namespace colmap_gcn {

// The --SiftMatching.* flags a user passes on to COLMAP, read for the
// matching and verification this project does itself
// (verification/), so that both follow the same settings as COLMAP's.

// The value of --SiftMatching.<name> in COLMAP arguments ("--x v" or
// "--x=v"; the last one wins), or `fallback`; throws Error for a value that
// is not a number.
double SiftMatchingValue(const std::vector<std::string>& colmap_args,
                         const std::string& name,
                         double fallback);

// `defaults` with max_ratio, max_distance and cross_check from the flags;
// checked.
ExactMatchingOptions ExactMatchingFromFlags(
    const ExactMatchingOptions& defaults,
    const std::vector<std::string>& colmap_args);

// `defaults` with num_threads, max_error, confidence, max_num_trials and
// min_inlier_ratio from the flags and `min_num_inliers`; checked.
ExactVerificationOptions ExactVerificationFromFlags(
    const ExactVerificationOptions& defaults,
    const std::vector<std::string>& colmap_args,
    int min_num_inliers);

}  // namespace colmap_gcn

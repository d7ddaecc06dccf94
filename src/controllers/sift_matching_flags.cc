#include "controllers/sift_matching_flags.h"

#include <exception>

#include "util/error.h"

namespace colmap_gcn {

double SiftMatchingValue(const std::vector<std::string>& args,
                         const std::string& name,
                         const double fallback) {
  const std::string flag = "--SiftMatching." + name;
  double value = fallback;
  for (size_t i = 0; i < args.size(); ++i) {
    std::string text;
    if (args[i] == flag && i + 1 < args.size()) {
      text = args[i + 1];
    } else if (args[i].rfind(flag + "=", 0) == 0) {
      text = args[i].substr(flag.size() + 1);
    } else {
      continue;
    }
    size_t end = 0;
    try {
      value = std::stod(text, &end);
    } catch (const std::exception&) {
      end = 0;
    }
    if (end == 0 || end != text.size()) {
      ThrowError(flag, " must be a number (got \"", text, "\")");
    }
  }
  return value;
}

ExactMatchingOptions ExactMatchingFromFlags(
    const ExactMatchingOptions& defaults,
    const std::vector<std::string>& args) {
  ExactMatchingOptions matching = defaults;
  matching.max_ratio = SiftMatchingValue(args, "max_ratio", matching.max_ratio);
  matching.max_distance =
      SiftMatchingValue(args, "max_distance", matching.max_distance);
  matching.cross_check =
      SiftMatchingValue(args, "cross_check", matching.cross_check ? 1 : 0) != 0;
  matching.Check();
  return matching;
}

ExactVerificationOptions ExactVerificationFromFlags(
    const ExactVerificationOptions& defaults,
    const std::vector<std::string>& args,
    const int min_num_inliers) {
  ExactVerificationOptions verification = defaults;
  verification.num_threads = static_cast<int>(
      SiftMatchingValue(args, "num_threads", verification.num_threads));
  verification.ransac.max_error =
      SiftMatchingValue(args, "max_error", verification.ransac.max_error);
  verification.ransac.confidence =
      SiftMatchingValue(args, "confidence", verification.ransac.confidence);
  verification.ransac.max_num_trials = static_cast<int>(SiftMatchingValue(
      args, "max_num_trials", verification.ransac.max_num_trials));
  verification.ransac.min_inlier_ratio = SiftMatchingValue(
      args, "min_inlier_ratio", verification.ransac.min_inlier_ratio);
  verification.min_num_inliers = min_num_inliers;
  verification.Check();
  return verification;
}

}  // namespace colmap_gcn

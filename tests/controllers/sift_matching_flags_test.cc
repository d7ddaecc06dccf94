#include "controllers/sift_matching_flags.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "util/error.h"

namespace colmap_gcn {
namespace {

TEST(SiftMatchingFlags, ReadsBothSpellingsAndTheLastValueWins) {
  const std::vector<std::string> args = {"--SiftMatching.max_ratio",
                                         "0.7",
                                         "--SiftMatching.use_gpu",
                                         "0",
                                         "--SiftMatching.max_ratio=0.6",
                                         "--SiftMatching.max_error=2.5"};
  EXPECT_DOUBLE_EQ(SiftMatchingValue(args, "max_ratio", 0.8), 0.6);
  EXPECT_DOUBLE_EQ(SiftMatchingValue(args, "max_error", 4), 2.5);
  EXPECT_DOUBLE_EQ(SiftMatchingValue(args, "confidence", 0.999), 0.999);
  // A longer flag sharing the prefix is another flag.
  EXPECT_DOUBLE_EQ(
      SiftMatchingValue({"--SiftMatching.max_ratio_x=0.1"}, "max_ratio", 0.8),
      0.8);
}

TEST(SiftMatchingFlags, ANonNumberNamesTheFlag) {
  try {
    SiftMatchingValue({"--SiftMatching.max_error", "4px"}, "max_error", 4);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("--SiftMatching.max_error"),
              std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("4px"), std::string::npos);
  }
}

TEST(SiftMatchingFlags, OptionsFollowTheFlagsAndAreChecked) {
  const std::vector<std::string> args = {"--SiftMatching.max_ratio=0.7",
                                         "--SiftMatching.cross_check=0",
                                         "--SiftMatching.max_num_trials=500",
                                         "--SiftMatching.num_threads=1"};
  const ExactMatchingOptions matching =
      ExactMatchingFromFlags(ExactMatchingOptions(), args);
  EXPECT_DOUBLE_EQ(matching.max_ratio, 0.7);
  EXPECT_DOUBLE_EQ(matching.max_distance, ExactMatchingOptions().max_distance);
  EXPECT_FALSE(matching.cross_check);
  const ExactVerificationOptions verification =
      ExactVerificationFromFlags(ExactVerificationOptions(), args, 30);
  EXPECT_EQ(verification.ransac.max_num_trials, 500);
  EXPECT_EQ(verification.num_threads, 1);
  EXPECT_EQ(verification.min_num_inliers, 30);
  EXPECT_THROW(ExactMatchingFromFlags(ExactMatchingOptions(),
                                      {"--SiftMatching.max_ratio=1.5"}),
               Error);
}

}  // namespace
}  // namespace colmap_gcn

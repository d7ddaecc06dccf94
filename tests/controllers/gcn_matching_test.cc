#include "controllers/gcn_model_pairing.h"

#include <gtest/gtest.h>

namespace colmap_gcn {
namespace {

TEST(GcnMatching, WarnsOnlyWhenEveryCandidateWasKept) {
  GcnPairingStats stats;
  EXPECT_EQ(GcnKeptEveryCandidateWarning(stats, 40), "");  // nothing scored
  stats.num_candidates = 10;
  stats.num_above_threshold = 9;
  EXPECT_EQ(GcnKeptEveryCandidateWarning(stats, 40), "");
  stats.num_above_threshold = 10;
  const std::string warning = GcnKeptEveryCandidateWarning(stats, 40);
  EXPECT_EQ(warning.rfind("gcn_matcher: warning: all 10 candidate pairs", 0),
            0u)
      << warning;
  EXPECT_NE(warning.find("k1 = 40"), std::string::npos) << warning;
  // The two ways out the model card measured: a higher threshold for
  // collections of unrelated places, a small k for duplicate structure.
  EXPECT_NE(warning.find("--GcnMatching.threshold 0.9"), std::string::npos)
      << warning;
  EXPECT_NE(warning.find("--GcnMatching.k 5"), std::string::npos) << warning;
  EXPECT_EQ(warning.find('\n'), std::string::npos) << warning;
}

}  // namespace
}  // namespace colmap_gcn

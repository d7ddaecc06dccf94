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
  // LOG(WARNING) adds the level and source; the message starts with what.
  EXPECT_EQ(warning.rfind("all 10 candidate pairs", 0), 0u) << warning;
  EXPECT_NE(warning.find("k1 = 40"), std::string::npos) << warning;
  // What to try depends on the model, so the model card says it.
  EXPECT_NE(warning.find("docs/model_card.md"), std::string::npos) << warning;
  EXPECT_EQ(warning.find('\n'), std::string::npos) << warning;
}

}  // namespace
}  // namespace colmap_gcn

#include "pairing/gcn_model_pairing.h"

#include <gtest/gtest.h>

namespace colmap_gcn {
namespace {

TEST(GcnMatching, WarnsOnlyWhenEveryCandidateWasKept) {
  GcnPairingStats stats;
  EXPECT_EQ(GcnKeptEveryCandidateWarning(stats, 40, 0.6, false),
            "");  // nothing scored
  stats.num_candidates = 10;
  stats.num_above_threshold = 9;
  EXPECT_EQ(GcnKeptEveryCandidateWarning(stats, 40, 0.6, false), "");
  stats.num_above_threshold = 10;
  const std::string warning =
      GcnKeptEveryCandidateWarning(stats, 40, 0.6, false);
  // LOG(WARNING) adds the level and source; the message starts with what.
  EXPECT_EQ(warning.rfind("all 10 candidate pairs", 0), 0u) << warning;
  EXPECT_NE(warning.find("k1 = 40"), std::string::npos) << warning;
  // What to try depends on the model, so the model card says it.
  EXPECT_NE(warning.find("docs/model_card.md"), std::string::npos) << warning;
  EXPECT_EQ(warning.find('\n'), std::string::npos) << warning;
}

// The threshold is named by where it came from: a user who set it (say to
// 0, which keeps everything) is not told the model is uncalibrated.
TEST(GcnMatching, KeptEveryCandidateWarningNamesTheThresholdsSource) {
  GcnPairingStats stats;
  stats.num_candidates = 10;
  stats.num_above_threshold = 10;
  const std::string model = GcnKeptEveryCandidateWarning(stats, 40, 0.6, false);
  EXPECT_NE(model.find("scored above the model's threshold 0.6: "),
            std::string::npos)
      << model;
  EXPECT_NE(model.find("not calibrated"), std::string::npos) << model;
  EXPECT_EQ(model.find("--GcnMatching.threshold"), std::string::npos) << model;

  const std::string flag = GcnKeptEveryCandidateWarning(stats, 40, 0, true);
  EXPECT_NE(flag.find("scored above --GcnMatching.threshold 0: "),
            std::string::npos)
      << flag;
  EXPECT_EQ(flag.find("the model's threshold"), std::string::npos) << flag;
  EXPECT_EQ(flag.find("not calibrated"), std::string::npos) << flag;
  EXPECT_NE(flag.find("a higher --GcnMatching.threshold keeps fewer"),
            std::string::npos)
      << flag;
  EXPECT_EQ(flag.find('\n'), std::string::npos) << flag;
}

}  // namespace
}  // namespace colmap_gcn

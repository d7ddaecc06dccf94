#include "math/precision_recall.h"

#include <gtest/gtest.h>

namespace colmap_gcn {
namespace {

TEST(PrecisionRecall, FromCounts) {
  const PrecisionRecall scores = ComputePrecisionRecall(3, 4, 6);
  EXPECT_DOUBLE_EQ(scores.precision, 0.75);
  EXPECT_DOUBLE_EQ(scores.recall, 0.5);
  EXPECT_DOUBLE_EQ(scores.f_measure, 0.6);
  EXPECT_DOUBLE_EQ(FMeasure(0.75, 0.5), 0.6);
}

TEST(PrecisionRecall, EmptySetsScoreZero) {
  const PrecisionRecall nothing_selected = ComputePrecisionRecall(0, 0, 5);
  EXPECT_EQ(nothing_selected.precision, 0.0);
  EXPECT_EQ(nothing_selected.recall, 0.0);
  EXPECT_EQ(nothing_selected.f_measure, 0.0);
  const PrecisionRecall nothing_relevant = ComputePrecisionRecall(0, 4, 0);
  EXPECT_EQ(nothing_relevant.precision, 0.0);
  EXPECT_EQ(nothing_relevant.recall, 0.0);
  EXPECT_EQ(FMeasure(0.0, 0.0), 0.0);
}

}  // namespace
}  // namespace colmap_gcn

#include "util/random.h"

#include <gtest/gtest.h>

namespace colmap_gcn {
namespace {

TEST(SplitMix64, MatchesTheReferenceStream) {
  // The first outputs of the reference implementation seeded with 0 and
  // with 1234567: synthetic scenes and cached results depend on them.
  uint64_t state = 0;
  EXPECT_EQ(SplitMix64(&state), 0xE220A8397B1DCDAFULL);
  EXPECT_EQ(SplitMix64(&state), 0x6E789E6AA1B965F4ULL);
  EXPECT_EQ(SplitMix64(&state), 0x06C45D188009454FULL);
  state = 1234567;
  EXPECT_EQ(SplitMix64(&state), 6457827717110365317ULL);
  EXPECT_EQ(SplitMix64(&state), 3203168211198807973ULL);
}

TEST(SplitMix64, StateAdvancesByTheIncrement) {
  uint64_t state = 5;
  SplitMix64(&state);
  EXPECT_EQ(state, 5 + kSplitMix64Increment);
  const uint64_t expected = SplitMix64Mix(state + kSplitMix64Increment);
  EXPECT_EQ(SplitMix64(&state), expected);
}

}  // namespace
}  // namespace colmap_gcn

#include "pairing/exhaustive_pairing.h"

#include <gtest/gtest.h>

#include <set>

#include "pairing/pairing_test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::MakeImages;

TEST(ExhaustivePairGenerator, EveryPairOnceForAnyBlockSize) {
  // Ids deliberately unordered and non-contiguous, as databases have them.
  const auto images = MakeImages({7, 2, 9, 4, 1, 12, 5, 3, 30, 8, 11});
  for (const int block_size : {2, 3, 4, 11, 50}) {
    ExhaustiveMatchingOptions options;
    options.block_size = block_size;
    ExhaustivePairGenerator generator(options, images);
    std::set<std::pair<image_t, image_t>> unique;
    size_t num_pairs = 0;
    size_t num_blocks = 0;
    while (!generator.HasFinished()) {
      const auto block = generator.Next();
      ++num_blocks;
      for (const auto& [a, b] : block) {
        EXPECT_LT(a, b);
        unique.emplace(a, b);
        ++num_pairs;
      }
    }
    EXPECT_EQ(num_pairs, 55u) << block_size;
    EXPECT_EQ(unique.size(), 55u) << block_size;
    EXPECT_GE(num_blocks, 1u);
    // AllPairs resets and drains again.
    EXPECT_EQ(generator.AllPairs().size(), 55u);
  }
}

TEST(ExhaustivePairGenerator, FewImages) {
  ExhaustiveMatchingOptions options;
  EXPECT_TRUE(
      ExhaustivePairGenerator(options, MakeImages({})).AllPairs().empty());
  EXPECT_TRUE(
      ExhaustivePairGenerator(options, MakeImages({3})).AllPairs().empty());
  EXPECT_EQ(ExhaustivePairGenerator(options, MakeImages({3, 1})).AllPairs(),
            (std::vector<ImagePair>{{1, 3}}));
  options.block_size = 1;
  EXPECT_THROW(ExhaustivePairGenerator(options, MakeImages({1, 2})), Error);
}

}  // namespace
}  // namespace colmap_gcn

#include "verification/exact_matching.h"

#include <gtest/gtest.h>

#include "test_features.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

using test::Perturbed;
using test::RandomDescriptorDirection;
using test::SetDescriptor;

TEST(ExactMatching, FindsEveryPerturbedCopyInShuffledOrder) {
  constexpr int kNum = 200;
  uint64_t state = 1;
  FeatureDescriptors d1(kNum, 128);
  FeatureDescriptors d2(kNum, 128);
  std::vector<Eigen::Matrix<float, 1, 128>> directions;
  for (int i = 0; i < kNum; ++i) {
    directions.push_back(RandomDescriptorDirection(&state));
    SetDescriptor(directions.back(), &d1, i);
  }
  // Image 2 holds the same features in another order: i -> (7 i + 3) % kNum.
  for (int i = 0; i < kNum; ++i) {
    SetDescriptor(
        Perturbed(directions[i], 0.1, &state), &d2, (7 * i + 3) % kNum);
  }
  const FeatureMatches matches =
      MatchDescriptorsExactly(d1, d2, ExactMatchingOptions());
  ASSERT_EQ(matches.rows(), kNum);
  for (int i = 0; i < kNum; ++i) {
    EXPECT_EQ(matches(i, 0), static_cast<uint32_t>(i));
    EXPECT_EQ(matches(i, 1), static_cast<uint32_t>((7 * i + 3) % kNum));
  }
}

TEST(ExactMatching, RatioTestDropsAFeatureWithTwoEqualCandidates) {
  uint64_t state = 2;
  FeatureDescriptors d1(2, 128);
  FeatureDescriptors d2(3, 128);
  const auto a = RandomDescriptorDirection(&state);
  const auto b = RandomDescriptorDirection(&state);
  SetDescriptor(a, &d1, 0);
  SetDescriptor(b, &d1, 1);
  // `a` appears twice in image 2 (a repeated structure): ambiguous.
  SetDescriptor(Perturbed(a, 0.05, &state), &d2, 0);
  SetDescriptor(Perturbed(a, 0.05, &state), &d2, 1);
  SetDescriptor(Perturbed(b, 0.05, &state), &d2, 2);
  const FeatureMatches matches =
      MatchDescriptorsExactly(d1, d2, ExactMatchingOptions());
  ASSERT_EQ(matches.rows(), 1);
  EXPECT_EQ(matches(0, 0), 1u);
  EXPECT_EQ(matches(0, 1), 2u);

  ExactMatchingOptions lenient;
  lenient.max_ratio = 1.0;
  lenient.cross_check = false;
  EXPECT_EQ(MatchDescriptorsExactly(d1, d2, lenient).rows(), 2);
}

TEST(ExactMatching, CrossCheckKeepsOnlyMutualBestMatches) {
  uint64_t state = 3;
  FeatureDescriptors d1(2, 128);
  FeatureDescriptors d2(1, 128);
  const auto a = RandomDescriptorDirection(&state);
  SetDescriptor(Perturbed(a, 0.02, &state), &d1, 0);
  SetDescriptor(Perturbed(a, 0.3, &state), &d1, 1);
  SetDescriptor(a, &d2, 0);
  ExactMatchingOptions options;
  options.max_ratio = 1.0;
  options.cross_check = false;
  EXPECT_EQ(MatchDescriptorsExactly(d1, d2, options).rows(), 2);
  options.cross_check = true;
  const FeatureMatches matches = MatchDescriptorsExactly(d1, d2, options);
  ASSERT_EQ(matches.rows(), 1);
  EXPECT_EQ(matches(0, 0), 0u);
}

TEST(ExactMatching, UnrelatedDescriptorsBeyondMaxDistanceDoNotMatch) {
  FeatureDescriptors d1 = FeatureDescriptors::Zero(1, 128);
  FeatureDescriptors d2 = FeatureDescriptors::Zero(1, 128);
  d1(0, 0) = 255;  // orthogonal directions: 90 degrees apart
  d2(0, 1) = 255;
  EXPECT_EQ(MatchDescriptorsExactly(d1, d2, ExactMatchingOptions()).rows(), 0);
  EXPECT_EQ(MatchDescriptorsExactly(
                FeatureDescriptors(0, 128), d2, ExactMatchingOptions())
                .rows(),
            0);
}

TEST(ExactMatching, CheckNamesTheBadOption) {
  ExactMatchingOptions options;
  options.max_ratio = 0;
  EXPECT_THROW(
      {
        try {
          options.Check();
        } catch (const Error& error) {
          EXPECT_NE(std::string(error.what()).find("max_ratio"),
                    std::string::npos);
          throw;
        }
      },
      Error);
}

}  // namespace
}  // namespace colmap_gcn

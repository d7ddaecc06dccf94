#include "controllers/adaptive_calibration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace colmap_gcn {
namespace {

struct Bounds {
  int min_strong_inliers = 30;
  int max_strong_inliers = 150;
};

int Cut(const std::vector<size_t>& inliers, const Bounds& bounds) {
  return LearnStrongInlierCut(
      inliers, bounds.min_strong_inliers, bounds.max_strong_inliers);
}

TEST(LearnStrongInlierCut, SplitsABimodalSampleBetweenItsModes) {
  Bounds options;
  std::vector<size_t> inliers;
  // Accidental verifications 15-35, real ones 176-3152 (log-spread).
  for (int i = 0; i < 60; ++i) inliers.push_back(15 + (i * 7) % 21);
  for (int i = 0; i < 40; ++i) {
    inliers.push_back(
        static_cast<size_t>(176 * std::pow(3152.0 / 176, i / 39.0)));
  }
  const int cut = Cut(inliers, options);
  EXPECT_GT(cut, 35);
  EXPECT_LE(cut, 150);  // max_strong_inliers
  options.max_strong_inliers = 1000;
  const int free_cut = Cut(inliers, options);
  EXPECT_GT(free_cut, 35);
  EXPECT_LT(free_cut, 176);
}

TEST(LearnStrongInlierCut, FloorWithoutTwoModesOrEnoughPairs) {
  Bounds options;
  options.min_strong_inliers = 40;
  // One log-normal-like mode of real pairs: no cut inside it.
  std::vector<size_t> real;
  for (int i = 0; i < 200; ++i) {
    const double z = std::sin(i * 12.9898) * 43758.5453;
    const double u = z - std::floor(z);
    const double v = std::fmod(i * 0.61803398875, 1.0);
    real.push_back(static_cast<size_t>(
        std::exp(6.0 + 0.6 * (u + v + std::fmod(i * 0.41421356, 1.0) - 1.5))));
  }
  EXPECT_EQ(Cut(real, options), 40);
  EXPECT_EQ(Cut({20, 20, 500, 600}, options), 40);
  // Two modes of real pairs (60-90 and 400-900 inliers): no accidents.
  std::vector<size_t> weak_and_strong;
  for (int i = 0; i < 40; ++i) {
    weak_and_strong.push_back(60 + (i * 7) % 31);
    weak_and_strong.push_back(400 + (i * 13) % 501);
  }
  EXPECT_EQ(Cut(weak_and_strong, options), 40);
  EXPECT_EQ(Cut({}, options), 40);
}

TEST(IsotonicCalibration, MonotoneShrunkAndDeterministic) {
  std::vector<std::pair<float, int>> samples;
  for (int i = 0; i < 100; ++i) {
    const float score = static_cast<float>(i) / 100.f;
    // Mostly positive above 0.5, with violations on both sides.
    const int label = (score > 0.5f) != (i % 9 == 0) ? 1 : 0;
    samples.emplace_back(score, label);
  }
  IsotonicCalibration a;
  a.Fit(samples);
  std::vector<std::pair<float, int>> shuffled(samples.rbegin(), samples.rend());
  std::rotate(shuffled.begin(), shuffled.begin() + 37, shuffled.end());
  IsotonicCalibration b;
  b.Fit(shuffled);
  double previous = -1;
  for (int i = -10; i <= 110; ++i) {
    const float score = static_cast<float>(i) / 100.f;
    const double p = a.Predict(score);
    EXPECT_GE(p, previous) << score;
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
    EXPECT_EQ(p, b.Predict(score)) << score;
    previous = p;
  }
  EXPECT_LT(a.Predict(0.1f), 0.25);
  EXPECT_GT(a.Predict(0.9f), 0.75);
  // Shrinkage: two positives alone do not make certainty.
  IsotonicCalibration two;
  two.Fit({{0.5f, 1}, {0.6f, 1}});
  EXPECT_LE(two.Predict(0.6f), 1.0);
  IsotonicCalibration empty;
  EXPECT_EQ(empty.Predict(0.5f), 0.0);
}

TEST(FitLogOddsOffset, RaisesAClassThatVerifiesMoreThanPredicted) {
  // Ten pairs predicted at 0.5, all positive: a raise, bounded by the prior.
  const std::vector<double> logits(10, 0.0);
  const double raise = FitLogOddsOffset(logits, 10);
  EXPECT_GT(raise, 0.5);
  EXPECT_LT(raise, 6.0);
  EXPECT_LT(FitLogOddsOffset(logits, 0), -0.5);
  EXPECT_NEAR(FitLogOddsOffset(logits, 5), 0.0, 1e-6);
  EXPECT_NEAR(Sigmoid(Logit(0.3)), 0.3, 1e-9);
}

TEST(RelativeLogOddsOffsets, OnlyWhatSetsAGroupApartFromTheOthers) {
  // Two groups predicted at 0.5: the first verifies 8 of 10, the second
  // 2 of 10. Together they verify as predicted, so the shared offset is 0
  // and each group keeps its own, of opposite sign.
  const std::vector<std::vector<double>> logits(2, std::vector<double>(10));
  std::vector<double> offsets = RelativeLogOddsOffsets(logits, {8, 2}, 10);
  ASSERT_EQ(offsets.size(), 2u);
  EXPECT_GT(offsets[0], 0.5);
  EXPECT_NEAR(offsets[1], -offsets[0], 1e-6);
  // Both fall short alike (3 of 10): the shortfall is shared, so each
  // keeps only what the shared offset's prior left of it.
  offsets = RelativeLogOddsOffsets(logits, {3, 3}, 10);
  EXPECT_NEAR(offsets[0], offsets[1], 1e-9);
  EXPECT_LT(std::abs(offsets[0]),
            0.5 * std::abs(FitLogOddsOffset(logits[0], 3)));
  // A group with too few samples gets none; the other is still relative
  // to all samples.
  const std::vector<std::vector<double>> uneven = {std::vector<double>(10),
                                                   std::vector<double>(4)};
  offsets = RelativeLogOddsOffsets(uneven, {10, 0}, 10);
  EXPECT_GT(offsets[0], 0.5);
  EXPECT_EQ(offsets[1], 0.0);
  EXPECT_EQ(RelativeLogOddsOffsets(uneven, {10, 0}, 20),
            std::vector<double>(2, 0.0));
}

TEST(IsRelativelyStrong, AgainstTheWeakerImagesBestPair) {
  // Best pairs of 800 and 200 inliers: the reference is 200.
  EXPECT_TRUE(IsRelativelyStrong(50, 800, 200, 0.25));
  EXPECT_FALSE(IsRelativelyStrong(49, 800, 200, 0.25));
  // A pair is its images' best: always strong.
  EXPECT_TRUE(IsRelativelyStrong(300, 300, 900, 0.25));
  // Ratio 0 asks nothing; an image without a verified pair neither.
  EXPECT_TRUE(IsRelativelyStrong(1, 800, 800, 0.0));
  EXPECT_TRUE(IsRelativelyStrong(1, 0, 800, 0.5));
}

TEST(PartnersStillWanted, UntilEnoughPartnersOrOutOfPatience) {
  EXPECT_EQ(PartnersStillWanted(0, 0, 3, 5), 3);
  EXPECT_EQ(PartnersStillWanted(2, 0, 3, 5), 1);
  EXPECT_EQ(PartnersStillWanted(3, 0, 3, 5), 0);
  EXPECT_EQ(PartnersStillWanted(7, 0, 3, 5), 0);
  // Patience left bounds it: 4 failures of 5 leave one attempt.
  EXPECT_EQ(PartnersStillWanted(0, 4, 3, 5), 1);
  EXPECT_EQ(PartnersStillWanted(0, 5, 3, 5), 0);
  EXPECT_EQ(PartnersStillWanted(0, 9, 3, 5), 0);
  EXPECT_EQ(PartnersStillWanted(0, 0, 0, 5), 0);
}

TEST(CountComponents, IsolatedVerticesAndChains) {
  EXPECT_EQ(CountComponents({}), 0u);
  EXPECT_EQ(CountComponents({{}, {}, {}}), 3u);
  // 0-1-2 chain, 3-4 pair, 5 alone; lists symmetric.
  const std::vector<std::vector<int>> graph = {{1}, {0, 2}, {1}, {4}, {3}, {}};
  EXPECT_EQ(CountComponents(graph), 3u);
  // A cycle counts once.
  EXPECT_EQ(CountComponents({{1, 2}, {0, 2}, {0, 1}}), 1u);
}

TEST(ComponentLabels, TheSmallestVertexOfEachComponent) {
  // 0-3-5 and 1-4 (joined from their larger ends first), 2 alone.
  const std::vector<std::vector<int>> graph = {{3}, {4}, {}, {5, 0}, {1}, {3}};
  EXPECT_EQ(ComponentLabels(graph), (std::vector<int>{0, 1, 2, 0, 1, 0}));
  EXPECT_TRUE(ComponentLabels({}).empty());
}

TEST(GrowthClusters, AnImageJoinsWithTwoPartnersInside) {
  // Triangles 0-1-2 and 2-3-4 share image 2: one connected graph, two
  // models. Seeds strongest first; an unknown or repeated seed is skipped.
  const std::vector<std::vector<int>> bowtie = {
      {1, 2}, {0, 2}, {0, 1, 3, 4}, {2, 4}, {2, 3}};
  EXPECT_EQ(CountComponents(bowtie), 1u);
  EXPECT_EQ(GrowthClusters(bowtie, {{0, 1}, {7, 1}, {3, 4}, {2, 3}}, 2),
            (std::vector<int>{0, 0, 0, 3, 3}));
  // At one view it is the connected component.
  EXPECT_EQ(GrowthClusters(bowtie, {{0, 1}}, 1),
            (std::vector<int>{0, 0, 0, 0, 0}));
  // A strip where each image overlaps the next two grows into one model;
  // an image without a seed is its own label.
  std::vector<std::vector<int>> strip(7);
  for (int i = 0; i < 6; ++i) {
    for (int j = i + 1; j <= std::min(5, i + 2); ++j) {
      strip[i].push_back(j);
      strip[j].push_back(i);
    }
  }
  EXPECT_EQ(GrowthClusters(strip, {{2, 3}}, 2),
            (std::vector<int>{2, 2, 2, 2, 2, 2, 6}));
  EXPECT_EQ(GrowthClusters(strip, {}, 2),
            (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
}

}  // namespace
}  // namespace colmap_gcn

#include "controllers/adaptive_pairing.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "adaptive_test_scenes.h"
#include "scene/colmap_scene_fixture.h"
#include "scene/database.h"
#include "test_utils.h"
#include "util/file.h"
#include "util/logging.h"

namespace colmap_gcn {
namespace {

using test::Flatten;
using test::LineScene;
using test::RingScene;
using test::RunToTheEnd;

TEST(AdaptivePairGenerator, SimulatedRunFindsTheStrongPairsAndStops) {
  const RingScene scene(40);
  AdaptivePairingOptions options;
  options.initial_per_image = 1;
  options.round_size = 20;
  AdaptivePairGenerator generator(options, scene.image_ids, scene.candidates);
  EXPECT_TRUE(generator.UsesVerification());
  const auto blocks = RunToTheEnd(
      &generator, [&](const ImagePair& pair) { return scene.Verify(pair); });
  ASSERT_TRUE(generator.HasFinished());
  EXPECT_GE(blocks.size(), 2u);
  const std::vector<ImagePair> pairs = Flatten(blocks);
  std::set<image_pair_t> unique;
  size_t strong = 0;
  for (const ImagePair& pair : pairs) {
    EXPECT_TRUE(
        unique.insert(ImagePairToPairId(pair.first, pair.second)).second);
    strong += scene.IsStrongPair(pair.first, pair.second) ? 1 : 0;
  }
  // 40 images x 3 strong neighbours each side / 2 = 120 strong pairs of
  // 240 candidates: all found, and far from all candidates attempted.
  EXPECT_EQ(strong, 120u);
  EXPECT_LT(pairs.size(), 200u);
  EXPECT_GT(generator.StrongCut(), 25);  // above the accidental ones
  ASSERT_EQ(generator.Rounds().size(), blocks.size());
  for (size_t r = 1; r < blocks.size(); ++r) {
    EXPECT_EQ(generator.Rounds()[r].num_pairs, blocks[r].size());
  }
  EXPECT_EQ(generator.Rounds().back().total_attempted, pairs.size());
  EXPECT_EQ(generator.Scores().size(), pairs.size());
}

TEST(AdaptivePairGenerator, LogsEveryRound) {
  struct Collect : LogSink {
    void Send(LogLevel, const std::string& message) override {
      if (message.find("adaptive round ") != std::string::npos) {
        lines.push_back(message);
      }
    }
    std::vector<std::string> lines;
  } sink;
  const RingScene scene(20);
  AdaptivePairGenerator generator(
      AdaptivePairingOptions(), scene.image_ids, scene.candidates);
  std::vector<std::vector<ImagePair>> blocks;
  {
    const ScopedLogSink scoped(&sink);
    blocks = RunToTheEnd(
        &generator, [&](const ImagePair& pair) { return scene.Verify(pair); });
  }
  ASSERT_EQ(sink.lines.size(), blocks.size());
  EXPECT_NE(sink.lines[0].find("adaptive round 1: "), std::string::npos);
  EXPECT_NE(sink.lines[0].find("calibrated yield n/a"), std::string::npos);
  EXPECT_NE(sink.lines[0].find(" strong (cut "), std::string::npos);
}

// Repeated structure: two look-alike groups of 12 images; one wrong pair
// across them verifies strongly. Blind propagation would then try every
// cross pair that closes a path through it; the calibrated one keeps to the
// low score the GCN gives cross pairs, which this collection shows to fail.
TEST(AdaptivePairGenerator, PropagationDoesNotSpreadAWrongStrongPair) {
  std::vector<image_t> image_ids;
  for (image_t id = 1; id <= 24; ++id) image_ids.push_back(id);
  const auto group = [](image_t id) { return id <= 12 ? 0 : 1; };
  std::vector<PairCandidate> candidates;
  for (image_t a = 1; a <= 24; ++a) {
    for (image_t b = a + 1; b <= 24; ++b) {
      const bool same = group(a) == group(b);
      const float wobble = 0.01f * static_cast<float>((a * 5 + b * 3) % 7);
      // The repeated structure fools the prior on 1-13 too.
      const float score = (a == 1 && b == 13) ? 0.95f
                          : same              ? 0.8f + wobble
                                              : 0.1f + wobble;
      candidates.push_back({a, b, score});
    }
  }
  const auto verify = [&](const ImagePair& pair) {
    PairVerification verification;
    verification.image_id1 = pair.first;
    verification.image_id2 = pair.second;
    const bool wrong_but_strong = std::min(pair.first, pair.second) == 1 &&
                                  std::max(pair.first, pair.second) == 13;
    if (group(pair.first) == group(pair.second) || wrong_but_strong) {
      verification.config = 2;
      verification.num_inliers = 400;
    } else if ((pair.first + pair.second) % 3 == 0) {
      verification.config = 2;
      verification.num_inliers = 20;  // accidental
    }
    return verification;
  };
  AdaptivePairingOptions options;
  options.isolated_retries = 0;
  // The enough rule: every pair within the groups; after round 1 the only
  // cross pairs are the bridging attempts (1-13 closes no strong triangle,
  // so the groups try to join), one per round, none strong.
  AdaptivePairGenerator enough(options, image_ids, candidates);
  const auto enough_blocks = RunToTheEnd(&enough, verify);
  size_t enough_within = 0;
  size_t enough_across = 0;
  for (size_t b = 0; b < enough_blocks.size(); ++b) {
    for (const ImagePair& pair : enough_blocks[b]) {
      const bool same = group(pair.first) == group(pair.second);
      enough_within += same ? 1 : 0;
      if (b == 0 || same) continue;
      ++enough_across;
      EXPECT_TRUE(enough.Rounds()[b].bridging)
          << pair.first << "-" << pair.second;
      EXPECT_EQ(enough.Rounds()[b].num_strong, 0u);
    }
  }
  EXPECT_EQ(enough_within, 2u * 66u);
  EXPECT_EQ(enough_across, static_cast<size_t>(options.component_patience));
  // The recall rule ends with one probe round.
  options.stop_rule = AdaptiveStopRule::kRecall;
  AdaptivePairGenerator generator(options, image_ids, candidates);
  const auto blocks = RunToTheEnd(&generator, verify);
  size_t within = 0;
  size_t across_after_first_round = 0;
  size_t through_wrong_pair = 0;  // cross pairs of image 1 or 13
  for (size_t b = 0; b < blocks.size(); ++b) {
    for (const ImagePair& pair : blocks[b]) {
      if (group(pair.first) == group(pair.second)) {
        ++within;
      } else if (b > 0) {
        ++across_after_first_round;
        const bool closes = pair.first == 1 || pair.second == 1 ||
                            pair.first == 13 || pair.second == 13;
        through_wrong_pair += closes ? 1 : 0;
      }
    }
  }
  // 1-13 is attempted in round 1 (both images' best) and verifies strongly.
  ASSERT_FALSE(blocks.empty());
  EXPECT_NE(std::find(blocks[0].begin(), blocks[0].end(), ImagePair(1, 13)),
            blocks[0].end());
  EXPECT_EQ(within, 2u * 66u);  // every pair within the groups
  // Blind propagation would try all 22 cross pairs that close a path
  // through 1-13 (1-y, x-13). Here cross pairs are tried only by the one
  // probe round (12 pairs) that ends the run, none verifying strongly.
  const std::vector<AdaptiveRound>& rounds = generator.Rounds();
  ASSERT_FALSE(rounds.empty());
  EXPECT_TRUE(rounds.back().probe);
  EXPECT_EQ(rounds.back().num_strong, 0u);
  EXPECT_EQ(across_after_first_round, rounds.back().num_pairs);
  EXPECT_LE(across_after_first_round, 12u);
  EXPECT_LT(through_wrong_pair, 6u);
}

TEST(AdaptivePairGenerator, EnoughStopsOnADenseCaptureWhereRecallDoesNot) {
  const LineScene scene(30);  // 435 pairs, all verifying
  AdaptivePairingOptions options;
  options.round_size = 30;
  options.relative_strength = 0.25;
  AdaptivePairGenerator enough(options, scene.image_ids, scene.candidates);
  const auto enough_pairs = Flatten(RunToTheEnd(&enough, &LineScene::Verify));
  options.stop_rule = AdaptiveStopRule::kRecall;
  AdaptivePairGenerator recall(options, scene.image_ids, scene.candidates);
  const auto recall_pairs = Flatten(RunToTheEnd(&recall, &LineScene::Verify));
  // The recall rule attempts almost everything; enough a fraction, with
  // every pair of distance <= 2 (>= 1/4 of the best pair's inliers).
  EXPECT_GT(recall_pairs.size(), 400u);
  EXPECT_LT(enough_pairs.size(), 150u);
  size_t close = 0;
  for (const ImagePair& pair : enough_pairs) {
    close += LineScene::Distance(pair) <= 2 ? 1 : 0;
  }
  EXPECT_EQ(close, 29u + 28u);
  EXPECT_EQ(enough.Rounds().back().num_components, 1u);
  // The two end images have only two partners within distance 2.
  EXPECT_EQ(enough.Rounds().back().num_connected, 28u);
}

TEST(AdaptivePairGenerator, ImagesWithEnoughStrongPartnersStopAskingForMore) {
  // A video-like capture: every pair of 60 images verifies strongly, so
  // the calibrated probability never falls below min_pair_yield and only
  // max_strong_partners ends the rounds.
  const LineScene scene(60);  // 1770 pairs
  const auto verify = [](const ImagePair& pair) {
    PairVerification verification = LineScene::Verify(pair);
    verification.num_inliers = 2000 * 10 / (10 + LineScene::Distance(pair));
    return verification;
  };
  AdaptivePairingOptions options;
  options.max_strong_partners = 0;
  AdaptivePairGenerator uncapped(options, scene.image_ids, scene.candidates);
  const auto uncapped_pairs = Flatten(RunToTheEnd(&uncapped, verify));
  options.max_strong_partners = 20;
  AdaptivePairGenerator capped(options, scene.image_ids, scene.candidates);
  const auto capped_pairs = Flatten(RunToTheEnd(&capped, verify));
  EXPECT_GT(uncapped_pairs.size(), 1700u);
  EXPECT_LT(capped_pairs.size(), 900u);
  std::map<image_t, int> partners;
  std::set<image_pair_t> attempted;
  for (const ImagePair& pair : capped_pairs) {
    ++partners[pair.first];
    ++partners[pair.second];
    attempted.insert(ImagePairToPairId(pair.first, pair.second));
  }
  for (const image_t image_id : scene.image_ids) {
    EXPECT_GE(partners[image_id], 20) << "image " << image_id;
  }
  // The partners kept are the most probable ones: the nearest.
  for (const PairCandidate& candidate : scene.candidates) {
    if (LineScene::Distance({candidate.image_id1, candidate.image_id2}) <= 5) {
      EXPECT_EQ(attempted.count(ImagePairToPairId(candidate.image_id1,
                                                  candidate.image_id2)),
                1u);
    }
  }
}

TEST(AdaptivePairGenerator, RejectedPairsAreNeitherStrongNorPartners) {
  const RingScene scene(24);
  AdaptivePairingOptions options;
  const auto rejected = [](image_t a, image_t b) {
    return std::min(a, b) == 1;  // every pair of image 1
  };
  AdaptivePairGenerator generator(options, scene.image_ids, scene.candidates);
  generator.SetPairRejection(rejected);
  const auto pairs = Flatten(RunToTheEnd(
      &generator, [&](const ImagePair& pair) { return scene.Verify(pair); }));
  size_t strong = 0;
  for (const ImagePair& pair : pairs) {
    strong += scene.IsStrongPair(pair.first, pair.second) &&
                      !rejected(pair.first, pair.second)
                  ? 1
                  : 0;
  }
  EXPECT_EQ(generator.Rounds().back().total_strong, strong);
  // Image 1 has no strong partner: 23 others, at least 2 components.
  EXPECT_GE(generator.Rounds().back().num_components, 2u);
}

TEST(AdaptivePairGenerator, SameObservationsGiveTheSameBlocks) {
  const RingScene scene(30);
  AdaptivePairingOptions options;
  options.round_size = 15;
  const auto verify = [&](const ImagePair& pair) { return scene.Verify(pair); };
  AdaptivePairGenerator first(options, scene.image_ids, scene.candidates);
  const auto blocks = RunToTheEnd(&first, verify);
  // A resumed run: a new generator fed the same results, and the same one
  // after Reset().
  AdaptivePairGenerator second(options, scene.image_ids, scene.candidates);
  EXPECT_EQ(RunToTheEnd(&second, verify), blocks);
  EXPECT_EQ(RunToTheEnd(&first, verify), blocks);
  // Results fed in another order within each block change nothing.
  AdaptivePairGenerator third(options, scene.image_ids, scene.candidates);
  std::vector<std::vector<ImagePair>> reordered;
  while (!third.HasFinished()) {
    reordered.push_back(third.Next());
    std::vector<PairVerification> results;
    for (auto it = reordered.back().rbegin(); it != reordered.back().rend();
         ++it) {
      results.push_back(verify(*it));
    }
    third.Observe(results);
  }
  EXPECT_EQ(reordered, blocks);
  // Another seed explores other pairs.
  options.seed = 5;
  AdaptivePairGenerator seeded(options, scene.image_ids, scene.candidates);
  seeded.Reset();
  EXPECT_NE(seeded.Next(), blocks.front());
}

// Two blocks of a photo walk, 1-30 and 31-60: photos up to 3 apart
// overlap, but the prior only knows each block, so the four junction pairs
// (28-31, 29-31, 29-32, 30-31, 30-32, 30-33) score as low as the 894
// pairs across that do not overlap. The walk's consecutive pairs verify
// more often than their scores predict; flagged as consecutive, the loop
// learns that and tries 30-31, which the prior alone never reaches.
struct TwoBlockWalk {
  TwoBlockWalk() {
    for (image_t id = 1; id <= 60; ++id) image_ids.push_back(id);
    for (image_t a = 1; a <= 60; ++a) {
      for (image_t b = a + 1; b <= 60; ++b) {
        const bool same = (a <= 30) == (b <= 30);
        const float wobble = 0.01f * static_cast<float>((a * 7 + b * 3) % 5);
        const float score =
            same ? 1.0f / static_cast<float>(b - a) - wobble : 0.05f + wobble;
        candidates.push_back({a, b, score, b == a + 1});
      }
    }
  }
  static bool Overlap(const ImagePair& pair) {
    return std::abs(static_cast<int>(pair.first) -
                    static_cast<int>(pair.second)) <= 3;
  }
  static bool Junction(const ImagePair& pair) {
    return Overlap(pair) && (std::min(pair.first, pair.second) <= 30) !=
                                (std::max(pair.first, pair.second) <= 30);
  }
  static PairVerification Verify(const ImagePair& pair) {
    return test::Verified(pair,
                          Overlap(pair)
                              ? 600 / std::abs(static_cast<int>(pair.first) -
                                               static_cast<int>(pair.second))
                              : 0);
  }
  std::vector<image_t> image_ids;
  std::vector<PairCandidate> candidates;
};

TEST(AdaptivePairGenerator, ConsecutivePairsLearnTheirOwnOffset) {
  const TwoBlockWalk walk;
  const auto junction_pairs = [&](std::vector<PairCandidate> candidates) {
    AdaptivePairGenerator generator(
        AdaptivePairingOptions(), walk.image_ids, candidates);
    const std::vector<ImagePair> pairs =
        Flatten(RunToTheEnd(&generator, [&](const ImagePair& pair) {
          return TwoBlockWalk::Verify(pair);
        }));
    return std::count_if(pairs.begin(), pairs.end(), TwoBlockWalk::Junction);
  };
  std::vector<PairCandidate> unflagged = walk.candidates;
  for (PairCandidate& candidate : unflagged) candidate.consecutive = false;
  EXPECT_EQ(junction_pairs(unflagged), 0);
  EXPECT_GE(junction_pairs(walk.candidates), 1);
}

// Two unrelated places of 30 photos each, where photos up to 6 apart
// overlap; the prior ranks place B's pairs four times lower than place A's
// at the same distance, so that B's overlapping pairs score like A's pairs
// that do not overlap. Pairs across places score lowest and never verify.
struct TwoPlaces {
  TwoPlaces() {
    for (image_t id = 1; id <= 60; ++id) image_ids.push_back(id);
    for (image_t a = 1; a <= 60; ++a) {
      for (image_t b = a + 1; b <= 60; ++b) {
        const float d = static_cast<float>(b - a);
        const float score =
            !SamePlace(a, b) ? 0.01f : (a <= 30 ? 1.0f / d : 0.25f / d);
        candidates.push_back({a, b, score});
      }
    }
  }
  static bool SamePlace(image_t a, image_t b) { return (a <= 30) == (b <= 30); }
  static bool Overlap(const ImagePair& pair) {
    return SamePlace(pair.first, pair.second) &&
           std::abs(static_cast<int>(pair.first) -
                    static_cast<int>(pair.second)) <= 6;
  }
  static PairVerification Verify(const ImagePair& pair) {
    return test::Verified(pair, Overlap(pair) ? 300 : 0);
  }
  std::vector<image_t> image_ids;
  std::vector<PairCandidate> candidates;
};

TEST(AdaptivePairGenerator, EachPlaceLearnsItsOwnYield) {
  const TwoPlaces places;
  AdaptivePairGenerator generator(
      AdaptivePairingOptions(), places.image_ids, places.candidates);
  const std::vector<ImagePair> pairs =
      Flatten(RunToTheEnd(&generator, [&](const ImagePair& pair) {
        return TwoPlaces::Verify(pair);
      }));
  int found_a = 0;
  int found_b = 0;
  for (const ImagePair& pair : pairs) {
    if (!TwoPlaces::Overlap(pair)) continue;
    ++(pair.first <= 30 ? found_a : found_b);
  }
  // 159 overlapping pairs in each place. With one calibration for both,
  // B's pairs look as unlikely as A's that do not overlap, and B stops
  // at 63 (its images' guaranteed partners and little more).
  EXPECT_GE(found_a, 150);
  EXPECT_GE(found_b, 150);
}

TEST(AddConsecutivePairs, MarksNameNeighboursAndAddsTheMissing) {
  const TemporaryDirectory dir("colmap_gcn_consecutive");
  const std::string path = JoinPaths(dir.Path(), "database.db");
  // Ids out of name order: the name order is the capture order.
  test::ExecuteSql(path,
                   std::string(test::kColmap38Schema) +
                       "INSERT INTO cameras VALUES (1, 0, 100, 80, NULL, 0);"
                       "INSERT INTO images (image_id, name, camera_id) VALUES "
                       "(1, 'c.jpg', 1), (2, 'a.jpg', 1), (3, 'b.jpg', 1), "
                       "(4, 'd.jpg', 1);");
  const Database database(path);
  // a-b (2-3) listed, b-c (3-1) and c-d (1-4) missing, 2-4 not consecutive.
  std::vector<PairCandidate> candidates = {{3, 2, 0.7f}, {2, 4, 0.9f}};
  AddConsecutivePairs(database, &candidates);
  ASSERT_EQ(candidates.size(), 4u);
  EXPECT_TRUE(candidates[0].consecutive);
  EXPECT_FLOAT_EQ(candidates[0].score, 0.7f);
  EXPECT_FALSE(candidates[1].consecutive);
  std::set<image_pair_t> added;
  for (size_t i = 2; i < candidates.size(); ++i) {
    EXPECT_TRUE(candidates[i].consecutive);
    EXPECT_EQ(candidates[i].score, 0.f);
    added.insert(
        ImagePairToPairId(candidates[i].image_id1, candidates[i].image_id2));
  }
  EXPECT_EQ(added,
            (std::set<image_pair_t>{ImagePairToPairId(1, 3),
                                    ImagePairToPairId(1, 4)}));
}

TEST(AdaptivePairGenerator, WithoutResultsOnlyTheFirstRound) {
  const RingScene scene(12);
  AdaptivePairingOptions options;
  options.initial_per_image = 2;
  options.exploration_fraction = 0;
  AdaptivePairGenerator generator(options, scene.image_ids, scene.candidates);
  const std::vector<ImagePair> pairs = generator.AllPairs();
  EXPECT_GE(pairs.size(), 12u);
  EXPECT_LE(pairs.size(), 24u);
  EXPECT_TRUE(generator.HasFinished());
}

// Round 1's exploration is a fraction of its size, but at most
// max_exploration_pairs: a larger collection gets no larger sample.
TEST(AdaptivePairGenerator, ExplorationIsCapped) {
  const RingScene scene(200);
  AdaptivePairingOptions options;
  options.initial_per_image = 2;
  const auto first_round = [&](int cap) {
    options.max_exploration_pairs = cap;
    AdaptivePairGenerator generator(options, scene.image_ids, scene.candidates);
    return generator.Next().size();
  };
  options.exploration_fraction = 0;
  const size_t best = first_round(0);
  options.exploration_fraction = 0.1;
  EXPECT_EQ(first_round(0), best + static_cast<size_t>(std::ceil(0.1 * best)));
  ASSERT_GT(std::ceil(0.1 * best), 10);
  EXPECT_EQ(first_round(10), best + 10);
}

TEST(AdaptivePairGenerator, BadInputIsAnError) {
  const RingScene scene(5);
  std::vector<PairCandidate> unknown = scene.candidates;
  unknown.push_back({1, 99, 0.5f});
  test::ExpectErrorContaining(
      [&] {
        AdaptivePairGenerator(
            AdaptivePairingOptions(), scene.image_ids, unknown);
      },
      "unknown image id");
}

TEST(CombinePriors, PercentilesOfBothListsOverTheirUnion) {
  // a: (1,2) best, (1,3) and (2,3) tied, duplicates keep the higher score.
  const std::vector<PairCandidate> a = {
      {1, 2, 0.9f}, {3, 1, 0.2f}, {2, 3, 0.2f}, {2, 1, 0.1f}};
  // b: (1,3) best, (3,4) only here; ranked within each image's list.
  const std::vector<PairCandidate> b = {{1, 3, 0.8f}, {4, 3, 0.5f}};
  const std::vector<PairCandidate> c = CombinePriors(a, b, 0.5);
  ASSERT_EQ(c.size(), 4u);
  const auto score = [&](image_t i, image_t j) {
    for (const PairCandidate& p : c) {
      if (p.image_id1 == i && p.image_id2 == j) return p.score;
    }
    ADD_FAILURE() << "no pair " << i << "-" << j;
    return -1.f;
  };
  // a: (1,3),(2,3) share percentile (1 + 2) / 2 / 3 = 1/2, (1,2) 1. b:
  // (1,3) is image 1's best and image 3's; (3,4) is image 3's second of
  // two (1/2) but image 4's only pair (1): the better image counts.
  EXPECT_FLOAT_EQ(score(1, 2), 0.5f);
  EXPECT_FLOAT_EQ(score(1, 3), 0.75f);
  EXPECT_FLOAT_EQ(score(2, 3), 0.25f);
  EXPECT_FLOAT_EQ(score(3, 4), 0.5f);
  // Sorted by (smaller id, larger id), the same in any input order.
  for (size_t i = 1; i < c.size(); ++i) {
    EXPECT_LT(std::make_pair(c[i - 1].image_id1, c[i - 1].image_id2),
              std::make_pair(c[i].image_id1, c[i].image_id2));
  }
  std::vector<PairCandidate> reversed(a.rbegin(), a.rend());
  const std::vector<PairCandidate> again = CombinePriors(reversed, b, 0.5);
  ASSERT_EQ(again.size(), c.size());
  for (size_t i = 0; i < c.size(); ++i) {
    EXPECT_EQ(again[i].image_id1, c[i].image_id1);
    EXPECT_FLOAT_EQ(again[i].score, c[i].score);
  }
  // Weight 0: a's percentiles alone; (1,2) sorts first.
  const std::vector<PairCandidate> only_a = CombinePriors(a, b, 0.0);
  EXPECT_FLOAT_EQ(only_a[0].score, 1.f);  // (1,2)
}

TEST(AdaptiveGcnPairingOptions, SimilarityWeightIsChecked) {
  AdaptiveGcnPairingOptions options;
  EXPECT_NO_THROW(options.Check());
  options.similarity_weight = 1.5;
  try {
    options.Check();
    ADD_FAILURE() << "no error";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find("similarity_weight"),
              std::string::npos)
        << error.what();
  }
}

TEST(AdaptivePairingOptions, CheckNamesTheField) {
  const auto expect =
      [](const std::function<void(AdaptivePairingOptions*)>& set,
         const std::string& field) {
        AdaptivePairingOptions options;
        set(&options);
        test::ExpectErrorContaining([&] { options.Check(); }, field);
      };
  expect([](AdaptivePairingOptions* o) { o->min_pair_yield = 1.5; },
         "min_pair_yield");
  expect([](AdaptivePairingOptions* o) { o->initial_per_image = 0; },
         "initial_per_image");
  expect([](AdaptivePairingOptions* o) { o->round_size = 0; }, "round_size");
  expect([](AdaptivePairingOptions* o) { o->max_num_pairs = -1; },
         "max_num_pairs");
  expect([](AdaptivePairingOptions* o) { o->max_strong_inliers = 10; },
         "max_strong_inliers");
  expect([](AdaptivePairingOptions* o) { o->exploration_fraction = -0.1; },
         "exploration_fraction");
  expect([](AdaptivePairingOptions* o) { o->max_exploration_pairs = -1; },
         "max_exploration_pairs");
  expect([](AdaptivePairingOptions* o) { o->isolated_retries = -1; },
         "isolated_retries");
  expect([](AdaptivePairingOptions* o) { o->relative_strength = 1.5; },
         "relative_strength");
  expect([](AdaptivePairingOptions* o) { o->min_strong_partners = -1; },
         "min_strong_partners");
  expect([](AdaptivePairingOptions* o) { o->image_patience = -1; },
         "image_patience");
  expect([](AdaptivePairingOptions* o) { o->max_strong_partners = 2; },
         "max_strong_partners");
  expect([](AdaptivePairingOptions* o) { o->component_patience = -1; },
         "component_patience");
  EXPECT_NO_THROW(AdaptivePairingOptions().Check());
}

}  // namespace
}  // namespace colmap_gcn

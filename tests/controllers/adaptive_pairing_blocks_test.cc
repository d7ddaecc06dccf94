#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <vector>

#include "adaptive_test_scenes.h"
#include "controllers/adaptive_pairing.h"
#include "scene/database.h"

namespace colmap_gcn {
namespace {

// The rounds that serve images and components the ranked rounds leave
// behind (adaptive_pairing_blocks.cc): connectivity, the per-image
// guarantee and bridging between strong components.

using test::Flatten;
using test::LineScene;
using test::RingScene;
using test::RunToTheEnd;

TEST(AdaptivePairGenerator, EveryImageGetsAPairAndIsolatedOnesRetries) {
  RingScene scene(20);
  // Image 21 has candidates but none of them verifies, all low-scored.
  scene.image_ids.push_back(21);
  for (image_t other = 1; other <= 6; ++other) {
    scene.candidates.push_back({21, other, 0.01f * static_cast<float>(other)});
  }
  AdaptivePairingOptions options;
  options.stop_rule = AdaptiveStopRule::kRecall;
  options.initial_per_image = 1;
  options.exploration_fraction = 0;
  options.isolated_retries = 2;
  AdaptivePairGenerator generator(options, scene.image_ids, scene.candidates);
  const auto pairs =
      Flatten(RunToTheEnd(&generator, [&](const ImagePair& pair) {
        if (pair.first != 21 && pair.second != 21) return scene.Verify(pair);
        PairVerification failed;
        failed.image_id1 = pair.first;
        failed.image_id2 = pair.second;
        return failed;
      }));
  std::map<image_t, int> attempts;
  for (const ImagePair& pair : pairs) {
    ++attempts[pair.first];
    ++attempts[pair.second];
  }
  for (const image_t id : scene.image_ids) EXPECT_GE(attempts[id], 1) << id;
  // Its best candidate in round 1, then two retries.
  EXPECT_EQ(attempts[21], 3);

  // A budget is hard, and round 1 cut by it keeps each image's best first.
  options.max_num_pairs = 21;
  AdaptivePairGenerator budget(options, scene.image_ids, scene.candidates);
  const auto budget_pairs = Flatten(RunToTheEnd(
      &budget, [&](const ImagePair& pair) { return scene.Verify(pair); }));
  EXPECT_EQ(budget_pairs.size(), 21u);
  std::set<image_t> covered;
  for (const ImagePair& pair : budget_pairs) {
    covered.insert(pair.first);
    covered.insert(pair.second);
  }
  EXPECT_EQ(covered.size(), scene.image_ids.size());
}

TEST(AdaptivePairGenerator, WeakImagesKeepTryingWithinTheirPatience) {
  RingScene scene(20);
  // Image 21: eight low-scored candidates; only the last (lowest) one
  // verifies, strongly. Image 22: six candidates, none verifies.
  scene.image_ids.push_back(21);
  scene.image_ids.push_back(22);
  for (image_t other = 1; other <= 8; ++other) {
    scene.candidates.push_back({21, other, 0.09f - 0.01f * other});
  }
  for (image_t other = 1; other <= 6; ++other) {
    scene.candidates.push_back({22, other, 0.09f - 0.01f * other});
  }
  const auto verify = [&](const ImagePair& pair) {
    PairVerification result;
    result.image_id1 = pair.first;
    result.image_id2 = pair.second;
    const image_t weak = std::max(pair.first, pair.second);
    const image_t other = std::min(pair.first, pair.second);
    if (weak <= 20) return scene.Verify(pair);
    if (weak == 21 && other == 8) {
      result.config = 2;
      result.num_inliers = 400;
    }
    return result;
  };
  AdaptivePairingOptions options;
  options.exploration_fraction = 0;
  options.image_patience = 8;
  AdaptivePairGenerator patient(options, scene.image_ids, scene.candidates);
  std::map<image_t, int> attempts;
  bool found = false;
  for (const ImagePair& pair : Flatten(RunToTheEnd(&patient, verify))) {
    for (const image_t id : {pair.first, pair.second}) ++attempts[id];
    found |= std::max(pair.first, pair.second) == 21 &&
             std::min(pair.first, pair.second) == 8;
  }
  EXPECT_TRUE(found);          // its partner at rank 8
  EXPECT_EQ(attempts[21], 8);  // all its candidates, no more exist
  EXPECT_EQ(attempts[22], 6);  // all its candidates, patience 8 not reached
  options.image_patience = 4;
  AdaptivePairGenerator impatient(options, scene.image_ids, scene.candidates);
  attempts.clear();
  for (const ImagePair& pair : Flatten(RunToTheEnd(&impatient, verify))) {
    for (const image_t id : {pair.first, pair.second}) ++attempts[id];
  }
  EXPECT_EQ(attempts[21], 4);
  EXPECT_EQ(attempts[22], 4);
}

// Two blocks of 12 images each (1-12, 13-24), every pair within a block
// verifying (strongly up to distance 4), and 20 low-scored candidates
// between them: (a, a + 12) and then (a, a + 13). None verifies but those
// within one image of `bridge` (its rank among them, -1: none) on both
// sides, with 400 inliers: two places photographed apart, or one place
// whose two halves only a few low-ranked candidates join.
struct TwoBlockScene {
  explicit TwoBlockScene(int bridge) {
    for (image_t i = 1; i <= 24; ++i) image_ids.push_back(i);
    for (image_t i = 1; i <= 24; ++i) {
      for (image_t j = i + 1; j <= 24; ++j) {
        if ((i <= 12) == (j <= 12)) {
          candidates.push_back({i, j, 1.0f / static_cast<float>(j - i)});
        }
      }
    }
    for (int k = 0; k < 20; ++k) {
      const image_t a = static_cast<image_t>(k < 12 ? k + 1 : k - 11);
      const image_t b = static_cast<image_t>(k < 12 ? a + 12 : a + 13);
      candidates.push_back({a, b, 0.02f - 0.0005f * static_cast<float>(k)});
      if (k == bridge) {
        bridge_pair = ImagePairToPairId(a, b);
        bridge_a = a;
        bridge_b = b;
      }
    }
  }
  static bool Crosses(const ImagePair& pair) {
    return (pair.first <= 12) != (pair.second <= 12);
  }
  PairVerification Verify(const ImagePair& pair) const {
    PairVerification verification;
    verification.image_id1 = pair.first;
    verification.image_id2 = pair.second;
    if (!Crosses(pair)) {
      const int d = LineScene::Distance(pair);
      verification.config = 2;
      verification.num_inliers = std::max(31, 1000 / (d * d));
    } else if (bridge_pair != 0 &&
               std::abs(static_cast<int>(std::min(pair.first, pair.second)) -
                        static_cast<int>(bridge_a)) <= 1 &&
               std::abs(static_cast<int>(std::max(pair.first, pair.second)) -
                        static_cast<int>(bridge_b)) <= 1) {
      verification.config = 2;
      verification.num_inliers = 400;
    }
    return verification;
  }
  std::vector<image_t> image_ids;
  std::vector<PairCandidate> candidates;
  image_pair_t bridge_pair = 0;
  image_t bridge_a = 0;
  image_t bridge_b = 0;
};

TEST(AdaptivePairGenerator, StrongComponentsKeepTryingToJoin) {
  AdaptivePairingOptions options;
  options.exploration_fraction = 0;  // no cross pair by chance
  const auto run = [&](const TwoBlockScene& scene,
                       int patience,
                       size_t* num_cross,
                       bool* found) {
    options.component_patience = patience;
    AdaptivePairGenerator generator(options, scene.image_ids, scene.candidates);
    *num_cross = 0;
    *found = false;
    for (const ImagePair& pair :
         Flatten(RunToTheEnd(&generator, [&](const ImagePair& p) {
           return scene.Verify(p);
         }))) {
      *num_cross += TwoBlockScene::Crosses(pair) ? 1 : 0;
      *found |=
          TwoBlockScene::Crosses(pair) && scene.Verify(pair).num_inliers > 0;
    }
    return generator.Rounds().back().num_components;
  };
  size_t num_cross = 0;
  bool found = false;
  // Joined around their third most probable candidate: without bridging
  // the rounds stop inside the blocks (every image has its strong
  // partners); with it, a lone strong bridge is followed by one beside it
  // that closes a strong triangle.
  const TwoBlockScene joined(/*bridge=*/2);
  EXPECT_EQ(run(joined, 0, &num_cross, &found), 2u);
  EXPECT_EQ(num_cross, 0u);
  EXPECT_FALSE(found);
  EXPECT_EQ(run(joined, 5, &num_cross, &found), 1u);
  EXPECT_TRUE(found);
  EXPECT_LE(num_cross, 5u);
  // Unrelated: the blocks spend their patience together, then stop.
  const TwoBlockScene apart(/*bridge=*/-1);
  EXPECT_EQ(run(apart, 5, &num_cross, &found), 2u);
  EXPECT_EQ(num_cross, 5u);
  // Beyond the patience: not found.
  const TwoBlockScene late(/*bridge=*/7);
  EXPECT_EQ(run(late, 5, &num_cross, &found), 2u);
  EXPECT_FALSE(found);
}

TEST(AdaptivePairGenerator, BlocksJoinedThroughOneImageStillBridge) {
  // Image 25 overlaps 11, 12 of one block and 13, 14 of the other: the
  // strong triangles 11-12-25 and 25-13-14 make one connected graph, but
  // a mapper grown from the first block registers 25 and stops at 13 (one
  // registered partner). The blocks still try their candidates between
  // them and find the bridge at rank 2.
  TwoBlockScene scene(/*bridge=*/2);
  scene.image_ids.push_back(25);
  for (const image_t other : {11, 12, 13, 14}) {
    scene.candidates.push_back({other, 25, 0.5f});
  }
  const auto verify = [&](const ImagePair& pair) {
    if (std::max(pair.first, pair.second) != 25) return scene.Verify(pair);
    PairVerification verification;
    verification.image_id1 = pair.first;
    verification.image_id2 = pair.second;
    verification.config = 2;
    verification.num_inliers = 400;
    return verification;
  };
  AdaptivePairingOptions options;
  options.exploration_fraction = 0;
  AdaptivePairGenerator generator(options, scene.image_ids, scene.candidates);
  size_t num_cross = 0;
  bool found = false;
  for (const ImagePair& pair : Flatten(RunToTheEnd(&generator, verify))) {
    if (std::max(pair.first, pair.second) == 25) continue;
    num_cross += TwoBlockScene::Crosses(pair) ? 1 : 0;
    found |= TwoBlockScene::Crosses(pair) && verify(pair).num_inliers > 0;
  }
  EXPECT_TRUE(found);
  EXPECT_LE(num_cross, 5u);
}

}  // namespace
}  // namespace colmap_gcn

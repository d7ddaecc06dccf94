#pragma once

#include <string>
#include <vector>

#include "pairing/pair_generator_spec.h"
#include "scene/database.h"
#include "util/types.h"

namespace colmap_gcn {

// The pair-generation framework mirrors COLMAP >= 3.10 (feature/pairing.h):
// a generator yields blocks of image pairs until HasFinished(); matchers
// consume the blocks. Generators here are built from the database's image
// list (the role of COLMAP's FeatureMatcherCache) so they port directly.

// What COLMAP's geometric verification made of one attempted pair, as its
// two_view_geometries row holds it (no row: config 0, 0 inliers).
struct PairVerification {
  image_t image_id1 = kInvalidImageId;
  image_t image_id2 = kInvalidImageId;
  int config = 0;
  size_t num_inliers = 0;
};

class PairGenerator {
 public:
  virtual ~PairGenerator() = default;

  virtual void Reset() = 0;

  virtual bool HasFinished() const = 0;

  virtual std::vector<ImagePair> Next() = 0;

  // Drains the generator from the start: every pair exactly once.
  std::vector<ImagePair> AllPairs();

  // One score per pair of AllPairs(), in its order, from generators that
  // score pairs (the pairs file's third column); empty otherwise.
  virtual std::vector<float> Scores() const { return {}; }

  // A one-line note for users about the pairs chosen; "" when there is
  // none.
  virtual std::string Warning() const { return ""; }

  // True for generators whose next block depends on how the previous ones
  // verified (adaptive pairing): the matcher then matches each block before
  // it asks for the next one and hands the results to Observe()
  // (controllers/MatchPairGenerator). Other generators are drained with
  // AllPairs() and matched in one go.
  virtual bool UsesVerification() const { return false; }

  // The verification results of pairs this generator handed out (any
  // order, each pair once); ignored by generators that do not use them.
  // Scores() then covers every pair handed out so far, in yield order.
  virtual void Observe(const std::vector<PairVerification>& verifications) {
    (void)verifications;
  }
};

// The next block of a generator's precomputed pair list, pairs[*pair_idx,
// *pair_idx + block_size), advancing *pair_idx: the Next() of generators
// that do all their work up front.
std::vector<ImagePair> NextPairBlock(const std::vector<ImagePair>& pairs,
                                     int block_size,
                                     size_t* pair_idx);

}  // namespace colmap_gcn

#pragma once

#include <memory>
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

struct ExhaustiveMatchingOptions {
  // Block size, i.e. number of images whose pairs form one block.
  int block_size = 50;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

struct ImagePairsMatchingOptions {
  // Number of image pairs in one block.
  int block_size = 1225;

  // Path to the pairs file (`name1 name2` per line, COLMAP's format).
  std::string match_list_path = "";

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

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

// All N(N-1)/2 pairs, in blocks of block_size x block_size images.
class ExhaustivePairGenerator : public PairGenerator {
 public:
  using PairOptions = ExhaustiveMatchingOptions;

  ExhaustivePairGenerator(const ExhaustiveMatchingOptions& options,
                          const std::vector<DatabaseImage>& images);
  ExhaustivePairGenerator(const ExhaustiveMatchingOptions& options,
                          const Database& database);

  void Reset() override;
  bool HasFinished() const override;
  std::vector<ImagePair> Next() override;

 private:
  const ExhaustiveMatchingOptions options_;
  std::vector<image_t> image_ids_;
  size_t block_size_;
  size_t num_blocks_;
  size_t start_idx1_ = 0;
  size_t start_idx2_ = 0;
};

// Pairs read from a pairs file, names resolved against the database. Unknown
// names are an error that lists them; self-pairs and duplicates (in either
// order) are dropped, as COLMAP does.
class ImportedPairGenerator : public PairGenerator {
 public:
  using PairOptions = ImagePairsMatchingOptions;

  ImportedPairGenerator(const ImagePairsMatchingOptions& options,
                        const std::vector<DatabaseImage>& images);
  ImportedPairGenerator(const ImagePairsMatchingOptions& options,
                        const Database& database);

  void Reset() override;
  bool HasFinished() const override;
  std::vector<ImagePair> Next() override;

 private:
  const ImagePairsMatchingOptions options_;
  std::vector<ImagePair> image_pairs_;
  size_t pair_idx_ = 0;
};

// --GcnMatching.pairing exhaustive and imported
// (--GcnMatching.match_list_path).
PairGeneratorSpec<ExhaustiveMatchingOptions> ExhaustivePairGeneratorSpec();
PairGeneratorSpec<ImagePairsMatchingOptions> ImportedPairGeneratorSpec();

}  // namespace colmap_gcn

#pragma once

#include <string>
#include <vector>

#include "pairing/pair_generator_spec.h"
#include "pairing/pairing.h"
#include "scene/database.h"

namespace colmap_gcn {

struct ExhaustiveMatchingOptions {
  // Block size, i.e. number of images whose pairs form one block.
  int block_size = 50;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

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

// --GcnMatching.pairing exhaustive.
PairGeneratorSpec<ExhaustiveMatchingOptions> ExhaustivePairGeneratorSpec();

}  // namespace colmap_gcn

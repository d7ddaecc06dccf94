#pragma once

#include <vector>

#include "pairing/pair_generator_spec.h"
#include "pairing/pairing.h"
#include "scene/database.h"

namespace colmap_gcn {

// COLMAP's sequential matching (SequentialMatchingOptions): images in name
// order, as frames of a video or a walk, each paired with the next ones.
struct SequentialMatchingOptions {
  // Each image is paired with the next `overlap` images in name order
  // (COLMAP's default).
  int overlap = 10;

  // Also pair each image with the images 2^j after it, j < overlap, as
  // COLMAP's quadratic_overlap (there on by default) does: loop closures
  // at growing distances for little extra cost.
  bool quadratic_overlap = false;

  // Number of image pairs in one block.
  int block_size = 1225;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// Sequential pairs, each unordered pair once, oriented (earlier, later) in
// name order, computed in the constructor.
class SequentialPairGenerator : public PairGenerator {
 public:
  using PairOptions = SequentialMatchingOptions;

  SequentialPairGenerator(const SequentialMatchingOptions& options,
                          const std::vector<DatabaseImage>& images);
  SequentialPairGenerator(const SequentialMatchingOptions& options,
                          const Database& database);

  void Reset() override;
  bool HasFinished() const override;
  std::vector<ImagePair> Next() override;

 private:
  const SequentialMatchingOptions options_;
  std::vector<ImagePair> image_pairs_;
  size_t pair_idx_ = 0;
};

// --GcnMatching.pairing sequential (--GcnMatching.sequential_overlap,
// sequential_quadratic_overlap); gcn_benchmark's "sequential:<k>" sets the
// overlap.
PairGeneratorSpec<SequentialMatchingOptions> SequentialPairGeneratorSpec();

}  // namespace colmap_gcn

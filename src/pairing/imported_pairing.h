#pragma once

#include <string>
#include <vector>

#include "pairing/pair_generator_spec.h"
#include "pairing/pairing.h"
#include "scene/database.h"

namespace colmap_gcn {

struct ImagePairsMatchingOptions {
  // Number of image pairs in one block.
  int block_size = 1225;

  // Path to the pairs file (`name1 name2` per line, COLMAP's format).
  std::string match_list_path = "";

  // Throws OptionError naming the first invalid field.
  void Check() const;
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

// --GcnMatching.pairing imported (--GcnMatching.match_list_path).
PairGeneratorSpec<ImagePairsMatchingOptions> ImportedPairGeneratorSpec();

}  // namespace colmap_gcn

#include "pairing/sequential_pairing.h"

#include <algorithm>
#include <memory>

#include "util/option_check.h"
#include "util/option_manager.h"

namespace colmap_gcn {

void SequentialMatchingOptions::Check() const {
  CHECK_OPTION_GE(overlap, 1);
  // 2^overlap must fit the image index.
  CHECK_OPTION(overlap,
               !quadratic_overlap || overlap <= 62,
               "be <= 62 with quadratic overlap");
  CHECK_OPTION_GE(block_size, 1);
}

SequentialPairGenerator::SequentialPairGenerator(
    const SequentialMatchingOptions& options,
    const std::vector<DatabaseImage>& images)
    : options_(options) {
  options_.Check();
  std::vector<DatabaseImage> sorted = images;
  std::sort(sorted.begin(),
            sorted.end(),
            [](const DatabaseImage& a, const DatabaseImage& b) {
              return a.name < b.name;
            });
  const size_t num_images = sorted.size();
  const size_t overlap = static_cast<size_t>(options_.overlap);
  for (size_t i = 0; i < num_images; ++i) {
    for (size_t j = i + 1; j < num_images && j <= i + overlap; ++j) {
      image_pairs_.emplace_back(sorted[i].image_id, sorted[j].image_id);
    }
    if (!options_.quadratic_overlap) continue;
    for (size_t power = 0; power < overlap; ++power) {
      const size_t j = i + (size_t{1} << power);
      if (j >= num_images) break;
      // Steps up to `overlap` are already linear pairs.
      if (j > i + overlap) {
        image_pairs_.emplace_back(sorted[i].image_id, sorted[j].image_id);
      }
    }
  }
}

SequentialPairGenerator::SequentialPairGenerator(
    const SequentialMatchingOptions& options, const Database& database)
    : SequentialPairGenerator(options, database.ReadAllImages()) {}

void SequentialPairGenerator::Reset() { pair_idx_ = 0; }

bool SequentialPairGenerator::HasFinished() const {
  return pair_idx_ >= image_pairs_.size();
}

std::vector<ImagePair> SequentialPairGenerator::Next() {
  return NextPairBlock(image_pairs_, options_.block_size, &pair_idx_);
}

PairGeneratorSpec<SequentialMatchingOptions> SequentialPairGeneratorSpec() {
  PairGeneratorSpec<SequentialMatchingOptions> spec;
  spec.name = "sequential";
  spec.add_options = [](OptionManager* manager,
                        SequentialMatchingOptions* options) {
    manager->AddDefaultOption("GcnMatching.sequential_overlap",
                              &options->overlap,
                              "sequential: next images (name order) paired");
    manager->AddDefaultOption("GcnMatching.sequential_quadratic_overlap",
                              &options->quadratic_overlap,
                              "sequential: also images 2^j later");
  };
  spec.create = [](const SequentialMatchingOptions& options,
                   const PairGeneratorContext& context) {
    return std::make_unique<SequentialPairGenerator>(options, context.database);
  };
  spec.depth = [](SequentialMatchingOptions* options) {
    return &options->overlap;
  };
  return spec;
}

}  // namespace colmap_gcn

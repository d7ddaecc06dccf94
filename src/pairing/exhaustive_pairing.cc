#include "pairing/exhaustive_pairing.h"

#include <algorithm>

#include "util/option_check.h"

namespace colmap_gcn {

void ExhaustiveMatchingOptions::Check() const {
  CHECK_OPTION_GE(block_size, 2);
}

namespace {

std::vector<image_t> SortedImageIds(const std::vector<DatabaseImage>& images) {
  std::vector<image_t> image_ids;
  image_ids.reserve(images.size());
  for (const auto& image : images) {
    image_ids.push_back(image.image_id);
  }
  std::sort(image_ids.begin(), image_ids.end());
  return image_ids;
}

}  // namespace

ExhaustivePairGenerator::ExhaustivePairGenerator(
    const ExhaustiveMatchingOptions& options,
    const std::vector<DatabaseImage>& images)
    : options_(options), image_ids_(SortedImageIds(images)) {
  options_.Check();
  block_size_ = static_cast<size_t>(options_.block_size);
  num_blocks_ = (image_ids_.size() + block_size_ - 1) / block_size_;
}

ExhaustivePairGenerator::ExhaustivePairGenerator(
    const ExhaustiveMatchingOptions& options, const Database& database)
    : ExhaustivePairGenerator(options, database.ReadAllImages()) {}

void ExhaustivePairGenerator::Reset() {
  start_idx1_ = 0;
  start_idx2_ = 0;
}

bool ExhaustivePairGenerator::HasFinished() const {
  return start_idx1_ >= image_ids_.size();
}

std::vector<ImagePair> ExhaustivePairGenerator::Next() {
  std::vector<ImagePair> pairs;
  if (HasFinished()) {
    return pairs;
  }
  const size_t end_idx1 =
      std::min(image_ids_.size(), start_idx1_ + block_size_);
  const size_t end_idx2 =
      std::min(image_ids_.size(), start_idx2_ + block_size_);
  // Only the upper triangle: each unordered pair once.
  for (size_t idx1 = start_idx1_; idx1 < end_idx1; ++idx1) {
    for (size_t idx2 = std::max(start_idx2_, idx1 + 1); idx2 < end_idx2;
         ++idx2) {
      pairs.emplace_back(image_ids_[idx1], image_ids_[idx2]);
    }
  }
  start_idx2_ += block_size_;
  if (start_idx2_ >= image_ids_.size()) {
    start_idx1_ += block_size_;
    start_idx2_ = start_idx1_;
  }
  return pairs;
}

PairGeneratorSpec<ExhaustiveMatchingOptions> ExhaustivePairGeneratorSpec() {
  PairGeneratorSpec<ExhaustiveMatchingOptions> spec;
  spec.name = "exhaustive";
  spec.create = [](const ExhaustiveMatchingOptions& options,
                   const PairGeneratorContext& context) {
    return std::make_unique<ExhaustivePairGenerator>(options, context.database);
  };
  return spec;
}

}  // namespace colmap_gcn

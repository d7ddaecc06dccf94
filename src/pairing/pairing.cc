#include "pairing/pairing.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "pairing/pairs_io.h"
#include "util/error.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

void ExhaustiveMatchingOptions::Check() const {
  CHECK_OPTION_GE(block_size, 2);
}

void ImagePairsMatchingOptions::Check() const {
  CHECK_OPTION_GE(block_size, 1);
  CHECK_OPTION(match_list_path, !match_list_path.empty(), "name a pairs file");
}

std::vector<ImagePair> PairGenerator::AllPairs() {
  Reset();
  std::vector<ImagePair> pairs;
  while (!HasFinished()) {
    const std::vector<ImagePair> block = Next();
    pairs.insert(pairs.end(), block.begin(), block.end());
  }
  return pairs;
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

ImportedPairGenerator::ImportedPairGenerator(
    const ImagePairsMatchingOptions& options,
    const std::vector<DatabaseImage>& images)
    : options_(options) {
  options_.Check();
  std::unordered_map<std::string, image_t> name_to_id;
  for (const auto& image : images) {
    name_to_id.emplace(image.name, image.image_id);
  }
  std::vector<std::string> unknown;
  std::unordered_set<image_pair_t> seen;
  const auto named_pairs = ReadPairsFile(options_.match_list_path);
  for (const auto& [name1, name2] : named_pairs) {
    const auto it1 = name_to_id.find(name1);
    const auto it2 = name_to_id.find(name2);
    for (const auto& [it, name] :
         {std::make_pair(it1, name1), std::make_pair(it2, name2)}) {
      if (it == name_to_id.end() &&
          std::find(unknown.begin(), unknown.end(), name) == unknown.end()) {
        unknown.push_back(name);
      }
    }
    if (it1 == name_to_id.end() || it2 == name_to_id.end() ||
        it1->second == it2->second) {
      continue;
    }
    if (seen.insert(ImagePairToPairId(it1->second, it2->second)).second) {
      image_pairs_.emplace_back(it1->second, it2->second);
    }
  }
  if (!unknown.empty()) {
    const size_t kMaxListed = 5;
    std::vector<std::string> listed(
        unknown.begin(),
        unknown.begin() + std::min(unknown.size(), kMaxListed));
    ThrowError(options_.match_list_path,
               ": ",
               unknown.size(),
               " image name(s) not in the database: ",
               StringJoin(listed, ", "),
               unknown.size() > kMaxListed ? ", ..." : "");
  }
  // Matching nothing and reporting success would hide a wrong file.
  if (image_pairs_.empty()) {
    ThrowError(options_.match_list_path,
               named_pairs.empty()
                   ? " lists no image pairs"
                   : " lists only pairs of an image with itself (" +
                         std::to_string(named_pairs.size()) + " lines)",
               "; nothing to match");
  }
}

std::vector<ImagePair> NextPairBlock(const std::vector<ImagePair>& pairs,
                                     const int block_size,
                                     size_t* pair_idx) {
  const size_t begin = std::min(*pair_idx, pairs.size());
  const size_t end =
      std::min(pairs.size(), begin + static_cast<size_t>(block_size));
  *pair_idx = end;
  return std::vector<ImagePair>(pairs.begin() + begin, pairs.begin() + end);
}

ImportedPairGenerator::ImportedPairGenerator(
    const ImagePairsMatchingOptions& options, const Database& database)
    : ImportedPairGenerator(options, database.ReadAllImages()) {}

void ImportedPairGenerator::Reset() { pair_idx_ = 0; }

bool ImportedPairGenerator::HasFinished() const {
  return pair_idx_ >= image_pairs_.size();
}

std::vector<ImagePair> ImportedPairGenerator::Next() {
  return NextPairBlock(image_pairs_, options_.block_size, &pair_idx_);
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

PairGeneratorSpec<ImagePairsMatchingOptions> ImportedPairGeneratorSpec() {
  PairGeneratorSpec<ImagePairsMatchingOptions> spec;
  spec.name = "imported";
  spec.add_options = [](OptionManager* manager,
                        ImagePairsMatchingOptions* options) {
    manager->AddDefaultOption("GcnMatching.match_list_path",
                              &options->match_list_path,
                              "pairs file for pairing=imported");
  };
  spec.create = [](const ImagePairsMatchingOptions& options,
                   const PairGeneratorContext& context) {
    return std::make_unique<ImportedPairGenerator>(options, context.database);
  };
  // A user's pairs file; gcn_benchmark's oracle imports the labels.
  spec.benchmark_method = false;
  return spec;
}

}  // namespace colmap_gcn

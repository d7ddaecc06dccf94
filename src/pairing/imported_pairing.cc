#include "pairing/imported_pairing.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

#include "pairing/pairs_io.h"
#include "util/error.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

void ImagePairsMatchingOptions::Check() const {
  CHECK_OPTION_GE(block_size, 1);
  CHECK_OPTION(match_list_path, !match_list_path.empty(), "name a pairs file");
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

#include "evaluation/adaptive_simulation.h"

#include <algorithm>
#include <set>
#include <unordered_set>

#include "evaluation/collection.h"
#include "util/error.h"

namespace colmap_gcn {

VerificationTable::VerificationTable(const Database& database)
    : images_(database.ReadAllImages()) {
  std::vector<std::string> names;
  for (size_t i = 0; i < images_.size(); ++i) {
    image_index_.emplace(images_[i].image_id, i);
    names.push_back(images_[i].name);
  }
  // A single scene's own names may contain "__" (web photos do).
  is_collection_ = IsMergedCollection(names);
  for (const TwoViewGeometryInfo& info : database.ReadTwoViewGeometryInfos()) {
    geometries_.emplace(info.pair_id, info);
  }
}

PairVerification VerificationTable::Lookup(image_t image_id1,
                                           image_t image_id2) const {
  PairVerification verification;
  verification.image_id1 = image_id1;
  verification.image_id2 = image_id2;
  const auto it = geometries_.find(ImagePairToPairId(image_id1, image_id2));
  if (it != geometries_.end()) {
    verification.config = it->second.config;
    verification.num_inliers = it->second.num_inliers;
  }
  return verification;
}

const std::string& VerificationTable::Name(image_t image_id) const {
  const auto it = image_index_.find(image_id);
  if (it == image_index_.end()) ThrowError("no image with id ", image_id);
  return images_[it->second].name;
}

std::vector<ImagePair> VerificationTable::StrongPairs(int strong_cut) const {
  std::vector<ImagePair> pairs;
  for (const auto& [pair_id, info] : geometries_) {
    if (!IsVerifiedTwoViewGeometry(info.config, info.num_inliers) ||
        info.num_inliers < static_cast<size_t>(strong_cut)) {
      continue;
    }
    const ImagePair pair = PairIdToImagePair(pair_id);
    if (image_index_.count(pair.first) == 0 ||
        image_index_.count(pair.second) == 0) {
      continue;
    }
    pairs.push_back(pair);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

PairSetQuality EvaluatePairSet(const std::vector<ImagePair>& pairs,
                               const VerificationTable& table,
                               const PairLabels* labels,
                               int strong_cut) {
  PairSetQuality quality;
  std::unordered_set<image_pair_t> seen;
  std::set<image_t> with_strong;
  std::set<ImageNamePair> matchable_found;
  std::set<ImageNamePair> matchable;
  if (labels != nullptr) {
    for (const ImageNamePair& pair :
         labels->MatchablePairs(PairLabelOptions())) {
      matchable.insert(pair);
    }
    quality.num_matchable = matchable.size();
  }
  for (const ImagePair& pair : pairs) {
    if (pair.first == pair.second ||
        !seen.insert(ImagePairToPairId(pair.first, pair.second)).second) {
      continue;
    }
    ++quality.num_pairs;
    const PairVerification verification = table.Lookup(pair.first, pair.second);
    if (IsVerifiedTwoViewGeometry(verification.config,
                                  verification.num_inliers)) {
      ++quality.num_verified;
      if (verification.num_inliers >= static_cast<size_t>(strong_cut)) {
        ++quality.num_strong;
        with_strong.insert(pair.first);
        with_strong.insert(pair.second);
      }
    }
    const std::string& name1 = table.Name(pair.first);
    const std::string& name2 = table.Name(pair.second);
    if (table.IsCollection() &&
        CollectionScene(name1) != CollectionScene(name2)) {
      ++quality.num_cross_scene;
    }
    const ImageNamePair key = name1 < name2 ? ImageNamePair(name1, name2)
                                            : ImageNamePair(name2, name1);
    if (matchable.count(key) > 0) matchable_found.insert(key);
  }
  quality.num_matchable_found = matchable_found.size();
  quality.num_images_with_strong = with_strong.size();
  return quality;
}

std::vector<SimulatedRound> SimulatePairGenerator(
    PairGenerator* generator,
    const VerificationTable& table,
    const PairLabels* labels,
    int strong_cut,
    std::vector<ImagePair>* pairs) {
  THROW_CHECK(generator != nullptr && pairs != nullptr);
  pairs->clear();
  generator->Reset();
  std::vector<SimulatedRound> rounds;
  while (!generator->HasFinished()) {
    const std::vector<ImagePair> block = generator->Next();
    std::vector<PairVerification> verifications;
    verifications.reserve(block.size());
    for (const ImagePair& pair : block) {
      verifications.push_back(table.Lookup(pair.first, pair.second));
    }
    generator->Observe(verifications);
    pairs->insert(pairs->end(), block.begin(), block.end());
    SimulatedRound round;
    round.num_pairs = block.size();
    round.total = EvaluatePairSet(*pairs, table, labels, strong_cut);
    rounds.push_back(round);
  }
  return rounds;
}

}  // namespace colmap_gcn

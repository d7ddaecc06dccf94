#include "evaluation/adaptive_simulation.h"

#include <algorithm>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "controllers/adaptive_calibration.h"
#include "controllers/adaptive_pairing.h"
#include "evaluation/collection.h"
#include "pairing/gcn_model_pairing.h"
#include "pairing/knn_pairing.h"
#include "pairing/pairs_io.h"
#include "scene/database_copy.h"
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

void VerificationTable::Reverify(const TwoViewGeometryStore& database,
                                 const ExactVerificationOptions& options) {
  std::vector<image_pair_t> pair_ids;
  std::vector<ImagePair> pairs;
  for (const auto& [pair_id, info] : geometries_) pair_ids.push_back(pair_id);
  std::sort(pair_ids.begin(), pair_ids.end());
  for (const image_pair_t pair_id : pair_ids) {
    pairs.push_back(PairIdToImagePair(pair_id));
  }
  const std::vector<VerifiedTwoViewGeometry> verified =
      VerifyPairsExactly(database, pairs, options);
  for (const VerifiedTwoViewGeometry& geometry : verified) {
    TwoViewGeometryInfo& info = geometries_.at(geometry.pair_id);
    info.config = geometry.config;
    info.num_inliers = geometry.inliers.rows();
  }
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

namespace {

size_t LargestGrownModel(std::vector<std::pair<ImagePair, size_t>> strong) {
  std::stable_sort(
      strong.begin(), strong.end(), [](const auto& a, const auto& b) {
        return a.second > b.second;
      });
  std::unordered_map<image_t, int> rows;
  std::vector<std::vector<int>> neighbours;
  std::vector<std::pair<int, int>> seeds;
  const auto row = [&](image_t image_id) {
    const auto [it, inserted] =
        rows.emplace(image_id, static_cast<int>(neighbours.size()));
    if (inserted) neighbours.emplace_back();
    return it->second;
  };
  for (const auto& [pair, inliers] : strong) {
    const int a = row(pair.first);
    const int b = row(pair.second);
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
    seeds.emplace_back(a, b);
  }
  std::vector<size_t> size(neighbours.size(), 0);
  size_t largest = 0;
  for (const int label : GrowthClusters(neighbours, seeds, 2)) {
    largest = std::max(largest, ++size[label]);
  }
  return largest;
}

}  // namespace

PairSetQuality EvaluatePairSet(const std::vector<ImagePair>& pairs,
                               const VerificationTable& table,
                               const PairLabels* labels,
                               int strong_cut) {
  PairSetQuality quality;
  std::unordered_set<image_pair_t> seen;
  std::set<image_t> with_strong;
  std::set<ImageNamePair> matchable_found;
  std::set<ImageNamePair> matchable;
  std::vector<std::pair<ImagePair, size_t>> strong;  // with their inliers
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
        strong.push_back({pair, verification.num_inliers});
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
  quality.num_images_grown = LargestGrownModel(strong);
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

namespace {

// The first `count` distinct pairs of `candidates` in the given order.
std::vector<ImagePair> FirstPairs(const std::vector<PairCandidate>& candidates,
                                  size_t count) {
  std::vector<ImagePair> pairs;
  std::unordered_set<image_pair_t> seen;
  for (const PairCandidate& candidate : candidates) {
    if (pairs.size() >= count) break;
    if (candidate.image_id1 == candidate.image_id2) continue;
    if (seen.insert(ImagePairToPairId(candidate.image_id1, candidate.image_id2))
            .second) {
      pairs.emplace_back(candidate.image_id1, candidate.image_id2);
    }
  }
  return pairs;
}

// Nothing is written beside the database: every embedding cache off.
GcnMatchingOptions WithoutCaches(GcnMatchingOptions options) {
  options.generators.Get<AdaptiveGcnPairingOptions>("adaptive")
      .gcn.use_vlad_cache = false;
  options.generators.Get<AdaptiveGcnPairingOptions>("adaptive").knn.use_cache =
      false;
  options.generators.Get<AdaptiveGcnPairingOptions>("adaptive_recall")
      .gcn.use_vlad_cache = false;
  options.generators.Get<AdaptiveGcnPairingOptions>("adaptive_recall")
      .knn.use_cache = false;
  options.generators.Get<GcnModelPairingOptions>("gcn").use_vlad_cache = false;
  options.generators.Get<GraphMatchPairingOptions>("graphmatch").knn.use_cache =
      false;
  options.generators.Get<KnnPairingOptions>("knn").use_cache = false;
  return options;
}

// The GCN's candidates by decreasing score, cut at `count` pairs.
std::vector<ImagePair> GcnTopPairs(const GcnMatchingOptions& options,
                                   const Database& database,
                                   size_t count) {
  std::vector<image_t> image_ids;
  std::vector<PairCandidate> gcn = GcnModelCandidates(
      options.generators.Get<AdaptiveGcnPairingOptions>("adaptive").gcn,
      database,
      &image_ids);
  std::stable_sort(gcn.begin(),
                   gcn.end(),
                   [](const PairCandidate& a, const PairCandidate& b) {
                     return a.score > b.score;
                   });
  return FirstPairs(gcn, count);
}

// kNN at equal TAM: every image's nearest neighbour, then every image's
// second, ... (by similarity within a rank), cut at `count` pairs.
std::vector<ImagePair> KnnPairsByRank(const GcnMatchingOptions& options,
                                      const Database& database,
                                      size_t count) {
  const KnnPairingOptions& knn_options =
      options.generators.Get<GraphMatchPairingOptions>("graphmatch").knn;
  std::vector<image_t> image_ids;
  const std::vector<PairCandidate> knn =
      SimilarityCandidates(knn_options, database, &image_ids);
  const size_t n = image_ids.size();
  const size_t k = n == 0 ? 0 : knn.size() / n;
  std::vector<PairCandidate> by_rank;
  for (size_t rank = 0; rank < k; ++rank) {
    std::vector<PairCandidate> level;
    for (size_t i = 0; i < n; ++i) level.push_back(knn[i * k + rank]);
    std::stable_sort(level.begin(),
                     level.end(),
                     [](const PairCandidate& a, const PairCandidate& b) {
                       return a.score > b.score;
                     });
    by_rank.insert(by_rank.end(), level.begin(), level.end());
  }
  return FirstPairs(by_rank, count);
}

std::vector<ImagePair> AllPairs(const VerificationTable& table) {
  std::vector<ImagePair> all;
  for (size_t i = 0; i < table.Images().size(); ++i) {
    for (size_t j = i + 1; j < table.Images().size(); ++j) {
      all.emplace_back(table.Images()[i].image_id, table.Images()[j].image_id);
    }
  }
  return all;
}

// The baselines at the replayed generator's strong cut, after its own line.
std::vector<NamedPairSetQuality> CompareBaselines(
    const GcnMatchingOptions& options,
    const Database& database,
    const VerificationTable& table,
    const PairLabels* labels,
    int cut,
    const PairSetQuality& replayed) {
  auto evaluate = [&](const std::vector<ImagePair>& pairs) {
    return EvaluatePairSet(pairs, table, labels, cut);
  };
  std::vector<NamedPairSetQuality> lines;
  lines.push_back({options.pairing, replayed});
  lines.push_back(
      {"gcn top-TAM scores",
       evaluate(GcnTopPairs(options, database, replayed.num_pairs))});
  GcnMatchingOptions single = options;
  single.pairing = "gcn";
  lines.push_back(
      {"gcn (model threshold)",
       evaluate(CreatePairGenerator(single, database)->AllPairs())});
  lines.push_back(
      {"knn at equal TAM",
       evaluate(KnnPairsByRank(options, database, replayed.num_pairs))});
  for (const int k : {5, 10, 25}) {
    GcnMatchingOptions knn = options;
    knn.pairing = "knn";
    knn.generators.Get<KnnPairingOptions>("knn").k = k;
    lines.push_back({"knn:" + std::to_string(k),
                     evaluate(CreatePairGenerator(knn, database)->AllPairs())});
  }
  // Another loop in the same simulation, with the same options.
  const auto simulate_baseline = [&](const std::string& pairing) {
    GcnMatchingOptions baseline_options = options;
    baseline_options.pairing = pairing;
    std::unique_ptr<PairGenerator> baseline =
        CreatePairGenerator(baseline_options, database);
    std::vector<ImagePair> baseline_pairs;
    SimulatePairGenerator(baseline.get(), table, labels, cut, &baseline_pairs);
    lines.push_back({pairing, evaluate(baseline_pairs)});
  };
  // The same loop under the other stopping rule.
  if (options.pairing == "adaptive") simulate_baseline("adaptive_recall");
  if (options.pairing != "graphmatch") simulate_baseline("graphmatch");
  lines.push_back({"exhaustive", evaluate(AllPairs(table))});
  // The ceiling of a loop that learns from strong verifications only: the
  // labelled matchable pairs among them.
  lines.push_back(
      {"exhaustive, strong only", evaluate(table.StrongPairs(cut))});
  return lines;
}

}  // namespace

AdaptiveSimulationReport RunAdaptiveSimulation(
    const AdaptiveSimulationOptions& options) {
  const GcnMatchingOptions matching = WithoutCaches(options.matching);
  RecoverHotJournal(options.database_path);
  const Database database(options.database_path);
  VerificationTable table(database);
  if (options.exact_verification && table.NumGeometries() > 0) {
    table.Reverify(TwoViewGeometryStore(options.database_path),
                   ExactVerificationOptions());
  }
  // Without verifications every replayed pair would count as failed and the
  // table would be all zeros.
  if (table.NumGeometries() == 0) {
    ThrowError("database ",
               options.database_path,
               " was never matched (its two_view_geometries table is empty); "
               "gcn_adaptive_simulator replays verification from it: run "
               "colmap exhaustive_matcher on it first");
  }
  std::unique_ptr<PairLabels> labels;
  if (!options.labels_path.empty()) {
    labels =
        std::make_unique<PairLabels>(PairLabels::Read(options.labels_path));
  }
  std::unique_ptr<PairGenerator> generator =
      CreatePairGenerator(matching, database);
  if (!generator->UsesVerification()) {
    ThrowError("--GcnMatching.pairing ",
               matching.pairing,
               " does not use verification; simulate adaptive or graphmatch");
  }
  std::vector<ImagePair> pairs;
  const std::vector<SimulatedRound> rounds =
      SimulatePairGenerator(generator.get(), table, labels.get(), 1, &pairs);
  const auto* adaptive = dynamic_cast<AdaptivePairGenerator*>(generator.get());
  if (!options.matching.matching.pairs_path.empty()) {  // in yield order
    WritePairsFile(options.matching.matching.pairs_path, pairs, table.Images());
  }

  AdaptiveSimulationReport report;
  report.num_images = table.Images().size();
  report.strong_cut = adaptive != nullptr ? adaptive->StrongCut() : 1;
  size_t end = 0;
  for (size_t r = 0; r < rounds.size(); ++r) {
    end += rounds[r].num_pairs;
    const std::vector<ImagePair> prefix(pairs.begin(), pairs.begin() + end);
    report.rounds.push_back(
        {"round " + std::to_string(r + 1) + " (+" +
             std::to_string(rounds[r].num_pairs) + ")",
         EvaluatePairSet(prefix, table, labels.get(), report.strong_cut)});
  }
  if (options.compare) {
    report.comparisons = CompareBaselines(
        matching,
        database,
        table,
        labels.get(),
        report.strong_cut,
        EvaluatePairSet(pairs, table, labels.get(), report.strong_cut));
  }
  return report;
}

}  // namespace colmap_gcn

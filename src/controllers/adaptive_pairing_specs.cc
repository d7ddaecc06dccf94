#include <algorithm>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "controllers/adaptive_pairing.h"
#include "pairing/sequential_pairing.h"
#include "retrieval/global_descriptors.h"
#include "retrieval/knn.h"
#include "util/option_check.h"
#include "util/option_manager.h"

// The adaptive and graphmatch pairings' candidates, priors, options and
// registrations (controllers/adaptive_pairing.h).

namespace colmap_gcn {

AdaptiveGcnPairingOptions::AdaptiveGcnPairingOptions() {
  gcn.k1 = 100;
  knn.k = 100;
}

void AdaptiveGcnPairingOptions::Check() const {
  gcn.Check();
  adaptive.Check();
  CHECK_OPTION_RANGE(similarity_weight, 0.0, 1.0);
  if (similarity_weight > 0) knn.Check();
}

namespace {

// Each unordered pair's score, the higher of a duplicate kept, by pair id.
std::unordered_map<image_pair_t, float> BestScores(
    const std::vector<PairCandidate>& candidates) {
  std::unordered_map<image_pair_t, float> best;
  for (const PairCandidate& candidate : candidates) {
    if (candidate.image_id1 == candidate.image_id2) continue;
    const auto [it, inserted] = best.emplace(
        ImagePairToPairId(candidate.image_id1, candidate.image_id2),
        candidate.score);
    if (!inserted) it->second = std::max(it->second, candidate.score);
  }
  return best;
}

// The percentile in (0, 1] of `score` among `sorted` scores (which hold
// it); ties share their mean percentile.
double MidRankPercentile(const std::vector<float>& sorted, float score) {
  const double low = static_cast<double>(
      std::lower_bound(sorted.begin(), sorted.end(), score) - sorted.begin());
  const double high = static_cast<double>(
      std::upper_bound(sorted.begin(), sorted.end(), score) - sorted.begin());
  return (low + high + 1) / (2 * static_cast<double>(sorted.size()));
}

// Each unordered pair's percentile within its list, by pair id.
std::unordered_map<image_pair_t, double> ScorePercentiles(
    const std::vector<PairCandidate>& candidates) {
  const std::unordered_map<image_pair_t, float> best = BestScores(candidates);
  std::vector<float> scores;
  scores.reserve(best.size());
  for (const auto& [pair_id, score] : best) scores.push_back(score);
  std::sort(scores.begin(), scores.end());
  std::unordered_map<image_pair_t, double> percentiles;
  for (const auto& [pair_id, score] : best) {
    percentiles.emplace(pair_id, MidRankPercentile(scores, score));
  }
  return percentiles;
}

// Each unordered pair's percentile within the better of its two images'
// own lists (the pairs of the list that include the image), by pair id:
// the way kNN retrieval ranks, so an image whose scores are all low still
// has its best pairs.
std::unordered_map<image_pair_t, double> ImageRankPercentiles(
    const std::vector<PairCandidate>& candidates) {
  const std::unordered_map<image_pair_t, float> best = BestScores(candidates);
  std::unordered_map<image_t, std::vector<float>> per_image;
  for (const auto& [pair_id, score] : best) {
    const ImagePair pair = PairIdToImagePair(pair_id);
    per_image[pair.first].push_back(score);
    per_image[pair.second].push_back(score);
  }
  for (auto& [image_id, scores] : per_image) {
    std::sort(scores.begin(), scores.end());
  }
  std::unordered_map<image_pair_t, double> percentiles;
  for (const auto& [pair_id, score] : best) {
    const ImagePair pair = PairIdToImagePair(pair_id);
    percentiles.emplace(
        pair_id,
        std::max(MidRankPercentile(per_image.at(pair.first), score),
                 MidRankPercentile(per_image.at(pair.second), score)));
  }
  return percentiles;
}

}  // namespace

std::vector<PairCandidate> CombinePriors(const std::vector<PairCandidate>& a,
                                         const std::vector<PairCandidate>& b,
                                         double weight_b) {
  const std::unordered_map<image_pair_t, double> pa = ScorePercentiles(a);
  const std::unordered_map<image_pair_t, double> pb = ImageRankPercentiles(b);
  std::vector<image_pair_t> pair_ids;
  for (const auto& [pair_id, p] : pa) pair_ids.push_back(pair_id);
  for (const auto& [pair_id, p] : pb) {
    if (pa.count(pair_id) == 0) pair_ids.push_back(pair_id);
  }
  // Pair ids order pairs by (smaller id, larger id).
  std::sort(pair_ids.begin(), pair_ids.end());
  std::vector<PairCandidate> combined;
  combined.reserve(pair_ids.size());
  for (const image_pair_t pair_id : pair_ids) {
    const auto ia = pa.find(pair_id);
    const auto ib = pb.find(pair_id);
    const double score = (1 - weight_b) * (ia != pa.end() ? ia->second : 0.0) +
                         weight_b * (ib != pb.end() ? ib->second : 0.0);
    const ImagePair pair = PairIdToImagePair(pair_id);
    combined.push_back({pair.first, pair.second, static_cast<float>(score)});
  }
  return combined;
}

void AddConsecutivePairs(const Database& database,
                         std::vector<PairCandidate>* candidates) {
  SequentialMatchingOptions sequential;
  sequential.overlap = 1;
  SequentialPairGenerator generator(sequential, database);
  std::unordered_set<image_pair_t> consecutive;
  while (!generator.HasFinished()) {
    for (const ImagePair& pair : generator.Next()) {
      consecutive.insert(ImagePairToPairId(pair.first, pair.second));
    }
  }
  for (PairCandidate& candidate : *candidates) {
    if (consecutive.erase(
            ImagePairToPairId(candidate.image_id1, candidate.image_id2)) > 0) {
      candidate.consecutive = true;
    }
  }
  // Sorted, so that the added candidates do not depend on hashing.
  std::vector<image_pair_t> missing(consecutive.begin(), consecutive.end());
  std::sort(missing.begin(), missing.end());
  for (const image_pair_t pair_id : missing) {
    const ImagePair pair = PairIdToImagePair(pair_id);
    candidates->push_back({pair.first, pair.second, 0.f, true});
  }
}

std::vector<PairCandidate> GcnModelCandidates(
    const GcnModelPairingOptions& options,
    const Database& database,
    std::vector<image_t>* image_ids) {
  std::vector<PairCandidate> candidates;
  for (const ScoredImagePair& pair :
       ScoreEveryGcnCandidate(options, database)) {
    candidates.push_back({pair.image_id1, pair.image_id2, pair.score});
  }
  image_ids->clear();
  for (const DatabaseImage& image : database.ReadAllImages()) {
    image_ids->push_back(image.image_id);
  }
  return candidates;
}

namespace {

void AddAdaptiveOptions(OptionManager* manager,
                        AdaptivePairingOptions* options) {
  manager->AddDefaultOption("GcnMatching.initial_per_image",
                            &options->initial_per_image,
                            "adaptive/graphmatch: round 1's best candidates "
                            "per image");
  manager->AddDefaultOption(
      "GcnMatching.exploration_fraction",
      &options->exploration_fraction,
      "adaptive/graphmatch: round 1's share of lower-ranked candidates");
  manager->AddDefaultOption(
      "GcnMatching.max_exploration_pairs",
      &options->max_exploration_pairs,
      "adaptive/graphmatch: at most this many of them; 0: no cap");
  manager->AddDefaultOption("GcnMatching.seed",
                            &options->seed,
                            "adaptive/graphmatch: seed of the exploration");
  manager->AddDefaultOption(
      "GcnMatching.round_size",
      &options->round_size,
      "adaptive/graphmatch: pairs per later round; -1: images (>= 50)");
  manager->AddDefaultOption(
      "GcnMatching.min_pair_yield",
      &options->min_pair_yield,
      "adaptive/graphmatch: stop when no candidate's calibrated P(strong "
      "verification) reaches this");
  manager->AddDefaultOption(
      "GcnMatching.max_num_pairs",
      &options->max_num_pairs,
      "adaptive/graphmatch: hard budget of attempted pairs; 0: none");
  manager->AddDefaultOption(
      "GcnMatching.min_strong_inliers",
      &options->min_strong_inliers,
      "adaptive/graphmatch: lowest learned strong-verification cut");
  manager->AddDefaultOption(
      "GcnMatching.max_strong_inliers",
      &options->max_strong_inliers,
      "adaptive/graphmatch: highest learned strong-verification cut");
  manager->AddDefaultOption(
      "GcnMatching.min_propagation_samples",
      &options->min_propagation_samples,
      "adaptive/graphmatch: matched path-closing pairs before propagation "
      "is calibrated on its own");
  manager->AddDefaultOption(
      "GcnMatching.isolated_retries",
      &options->isolated_retries,
      "adaptive_recall/graphmatch: extra attempts for images without a "
      "strong pair");
  manager->AddDefaultOption(
      "GcnMatching.relative_strength",
      &options->relative_strength,
      "adaptive: a strong pair holds at least this share of the inliers of "
      "its weaker image's best verified pair");
  manager->AddDefaultOption(
      "GcnMatching.min_strong_partners",
      &options->min_strong_partners,
      "adaptive: strong partners every image keeps trying to reach");
  manager->AddDefaultOption(
      "GcnMatching.image_patience",
      &options->image_patience,
      "adaptive: attempts without a strong verification after which an "
      "image stops trying");
  manager->AddDefaultOption(
      "GcnMatching.max_strong_partners",
      &options->max_strong_partners,
      "adaptive: strong partners after which an image has enough for the "
      "mapper; 0: no cap");
  manager->AddDefaultOption(
      "GcnMatching.component_patience",
      &options->component_patience,
      "adaptive: attempts each model the strong pairs can grow (>= 3 "
      "images) spends on joining another before the rounds stop; 0: none");
}

}  // namespace

namespace {

PairGeneratorSpec<AdaptiveGcnPairingOptions> AdaptiveSpec(
    const std::string& name, AdaptiveStopRule stop_rule) {
  PairGeneratorSpec<AdaptiveGcnPairingOptions> spec;
  spec.name = name;
  spec.add_options = [](OptionManager* manager,
                        AdaptiveGcnPairingOptions* options) {
    GcnModelPairGeneratorSpec().add_options(manager, &options->gcn);
    KnnPairGeneratorSpec().add_options(manager, &options->knn);
    AddAdaptiveOptions(manager, &options->adaptive);
    manager->AddDefaultOption(
        "GcnMatching.similarity_weight",
        &options->similarity_weight,
        "adaptive: weight of embedding similarity in the prior (percentiles "
        "of the GCN score and of the similarity); 0: the GCN score alone");
  };
  spec.uses_verification = true;
  spec.create = [name, stop_rule](const AdaptiveGcnPairingOptions& options,
                                  const PairGeneratorContext& context)
      -> std::unique_ptr<PairGenerator> {
    std::vector<image_t> image_ids;
    std::vector<PairCandidate> candidates =
        GcnModelCandidates(options.gcn, context.database, &image_ids);
    if (options.similarity_weight > 0) {
      std::vector<image_t> knn_image_ids;
      candidates = CombinePriors(
          candidates,
          SimilarityCandidates(options.knn, context.database, &knn_image_ids),
          options.similarity_weight);
    }
    AddConsecutivePairs(context.database, &candidates);
    AdaptivePairingOptions adaptive = options.adaptive;
    adaptive.stop_rule = stop_rule;
    return std::make_unique<AdaptivePairGenerator>(
        adaptive, image_ids, candidates, name);
  };
  return spec;
}

}  // namespace

PairGeneratorSpec<AdaptiveGcnPairingOptions> AdaptivePairGeneratorSpec() {
  return AdaptiveSpec("adaptive", AdaptiveStopRule::kEnough);
}

PairGeneratorSpec<AdaptiveGcnPairingOptions> AdaptiveRecallPairGeneratorSpec() {
  return AdaptiveSpec("adaptive_recall", AdaptiveStopRule::kRecall);
}

GraphMatchPairingOptions::GraphMatchPairingOptions() { knn.k = 100; }

void GraphMatchPairingOptions::Check() const {
  knn.Check();
  adaptive.Check();
}

std::vector<PairCandidate> SimilarityCandidates(
    const KnnPairingOptions& options,
    const Database& database,
    std::vector<image_t>* image_ids) {
  options.Check();
  GlobalDescriptorOptions descriptor_options = options.Descriptors();
  descriptor_options.num_threads = options.num_threads;
  descriptor_options.vlad.num_threads = options.num_threads;
  const EmbeddingMatrix embeddings =
      ComputeGlobalDescriptors(database, descriptor_options, image_ids);
  KnnOptions knn_options;
  knn_options.k = std::min<int>(
      options.k, std::max<int>(1, static_cast<int>(image_ids->size()) - 1));
  knn_options.num_threads = options.num_threads;
  knn_options.method = options.knn_method;
  std::vector<PairCandidate> candidates;
  if (image_ids->size() < 2) return candidates;
  const KnnGraph graph = ComputeKnn(embeddings, knn_options);
  for (int i = 0; i < graph.NumImages(); ++i) {
    for (int n = 0; n < graph.K(); ++n) {
      const int j = graph.indices(i, n);
      if (j < 0 || j == i) continue;
      candidates.push_back(
          {(*image_ids)[i], (*image_ids)[j], graph.similarities(i, n)});
    }
  }
  return candidates;
}

PairGeneratorSpec<GraphMatchPairingOptions> GraphMatchPairGeneratorSpec() {
  PairGeneratorSpec<GraphMatchPairingOptions> spec;
  spec.name = "graphmatch";
  spec.add_options = [](OptionManager* manager,
                        GraphMatchPairingOptions* options) {
    KnnPairGeneratorSpec().add_options(manager, &options->knn);
    AddAdaptiveOptions(manager, &options->adaptive);
  };
  spec.uses_verification = true;
  spec.create = [](const GraphMatchPairingOptions& options,
                   const PairGeneratorContext& context)
      -> std::unique_ptr<PairGenerator> {
    std::vector<image_t> image_ids;
    const std::vector<PairCandidate> candidates =
        SimilarityCandidates(options.knn, context.database, &image_ids);
    AdaptivePairingOptions adaptive = options.adaptive;
    adaptive.stop_rule = AdaptiveStopRule::kRecall;
    return std::make_unique<AdaptivePairGenerator>(
        adaptive, image_ids, candidates, "graphmatch");
  };
  return spec;
}

}  // namespace colmap_gcn

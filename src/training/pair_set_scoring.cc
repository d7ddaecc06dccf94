#include "training/pair_set_scoring.h"

#include <algorithm>
#include <unordered_set>

#include "pairing/gcn_pair_generator.h"
#include "pairing/knn_pairing.h"
#include "util/error.h"
#include "util/pair_key.h"
#include "util/threading.h"

namespace colmap_gcn {
namespace {

std::unordered_set<uint64_t> PairKeys(
    const std::vector<std::pair<int, int>>& pairs) {
  std::unordered_set<uint64_t> keys;
  for (const auto& [i, j] : pairs) keys.insert(PairKey(i, j));
  return keys;
}

}  // namespace

PairSetScore ScorePairSet(const std::vector<std::pair<int, int>>& pairs,
                          const GcnTrainingScene& scene) {
  const std::unordered_set<uint64_t> positives = PairKeys(scene.positive_pairs);
  const std::unordered_set<uint64_t> unrelated =
      PairKeys(scene.unrelated_pairs);
  return ScorePairSet(pairs, positives.size(), [&](int i, int j) {
    PairLabel label;
    label.matchable = positives.count(PairKey(i, j)) > 0;
    label.wrong = unrelated.count(PairKey(i, j)) > 0;
    label.cross_scene = !scene.part_of_row.empty() &&
                        scene.part_of_row[i] != scene.part_of_row[j];
    return label;
  });
}

std::vector<std::pair<int, int>> MostSimilarPairs(
    const EmbeddingMatrix& embeddings, size_t num_pairs) {
  const int n = static_cast<int>(embeddings.rows());
  const Eigen::MatrixXf similarity = embeddings * embeddings.transpose();
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) pairs.emplace_back(i, j);
  }
  num_pairs = std::min(num_pairs, pairs.size());
  std::partial_sort(pairs.begin(),
                    pairs.begin() + num_pairs,
                    pairs.end(),
                    [&](const auto& a, const auto& b) {
                      const float sa = similarity(a.first, a.second);
                      const float sb = similarity(b.first, b.second);
                      return sa != sb ? sa > sb : a < b;
                    });
  pairs.resize(num_pairs);
  return pairs;
}

std::vector<std::pair<int, int>> ShortestPrefixWithTruePositives(
    std::vector<std::pair<int, int>> ranked,
    const GcnTrainingScene& scene,
    size_t num_true_positives) {
  const std::unordered_set<uint64_t> positives = PairKeys(scene.positive_pairs);
  size_t prefix = 0;
  for (size_t found = 0; prefix < ranked.size() && found < num_true_positives;
       ++prefix) {
    found +=
        positives.count(PairKey(ranked[prefix].first, ranked[prefix].second));
  }
  ranked.resize(prefix);
  return ranked;
}

double BestPrecisionAtRecall(const std::vector<std::pair<int, int>>& ranked,
                             const GcnTrainingScene& scene,
                             double min_recall) {
  const std::unordered_set<uint64_t> positives = PairKeys(scene.positive_pairs);
  if (positives.empty()) return -1;
  std::unordered_set<uint64_t> seen;
  size_t num_true_positives = 0;
  double best = -1;
  for (const auto& [i, j] : ranked) {
    const uint64_t key = PairKey(i, j);
    if (i == j || !seen.insert(key).second) continue;
    num_true_positives += positives.count(key);
    const double recall =
        static_cast<double>(num_true_positives) / positives.size();
    if (recall >= min_recall) {
      best =
          std::max(best, static_cast<double>(num_true_positives) / seen.size());
    }
  }
  return best;
}

std::vector<std::pair<int, int>> TopKPairs(const KnnGraph& graph, int k) {
  const int n = graph.NumImages();
  k = std::min(k, graph.K());
  if (n < 2 || k <= 0) return {};
  // Rows are sorted by similarity: the top-k graph is the first k columns.
  KnnGraph top_k;
  top_k.indices = graph.indices.leftCols(k);
  top_k.similarities = graph.similarities.leftCols(k);
  // KnnPairGenerator's selection, with row indices as image ids.
  std::vector<image_t> rows(n);
  for (int i = 0; i < n; ++i) rows[i] = static_cast<image_t>(i);
  std::vector<std::pair<int, int>> pairs;
  for (const auto& [i, j] : KnnGraphToPairs(top_k, rows)) {
    pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
  }
  return pairs;
}

std::vector<std::pair<int, int>> TopKPairs(const EmbeddingMatrix& embeddings,
                                           int k,
                                           int num_threads) {
  const int n = static_cast<int>(embeddings.rows());
  if (n < 2 || k <= 0) return {};
  KnnOptions knn_options;
  knn_options.k = std::min(k, n - 1);
  knn_options.num_threads = num_threads;
  return TopKPairs(ComputeExactKnn(embeddings, knn_options), k);
}

std::vector<ScoredRowPair> GcnCandidatePairs(const GcnModel& model,
                                             const GcnTrainingScene& scene,
                                             int num_threads) {
  GcnPairingOptions options = EveryCandidate(GcnPairingOptionsFromModel(model));
  options.num_threads = num_threads;
  std::vector<image_t> ids(scene.embeddings.rows());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<image_t>(i + 1);
  GcnPairGenerator generator(options, ids, scene.embeddings, model);
  std::vector<ScoredRowPair> candidates;
  for (const auto& pair : generator.ScoredPairs()) {
    candidates.push_back({static_cast<int>(pair.image_id1) - 1,
                          static_cast<int>(pair.image_id2) - 1,
                          pair.score});
  }
  return candidates;
}

std::vector<uint8_t> MatchableFlags(
    const std::vector<ScoredRowPair>& candidates,
    const GcnTrainingScene& scene) {
  const std::unordered_set<uint64_t> positives = PairKeys(scene.positive_pairs);
  std::vector<uint8_t> flags;
  flags.reserve(candidates.size());
  for (const auto& candidate : candidates) {
    flags.push_back(positives.count(PairKey(candidate.row1, candidate.row2)));
  }
  return flags;
}

std::vector<std::pair<int, int>> PairsAtThreshold(
    const std::vector<ScoredRowPair>& candidates, float threshold) {
  std::vector<std::pair<int, int>> pairs;
  for (const auto& candidate : candidates) {
    if (candidate.score >= threshold) {
      pairs.emplace_back(candidate.row1, candidate.row2);
    }
  }
  return pairs;
}

float SelectGcnThreshold(const GcnModel& model,
                         const std::vector<GcnTrainingScene>& scenes,
                         int num_threads) {
  if (scenes.empty()) return model.info.threshold;
  std::vector<std::vector<ScoredRowPair>> candidates;
  for (const auto& scene : scenes) {
    candidates.push_back(GcnCandidatePairs(model, scene, num_threads));
  }
  float best_threshold = model.info.threshold;
  double best_f = -1;
  // Steps of 0.05, refined towards both ends: a model's scores on an
  // unfamiliar collection can crowd near 0 or 1.
  std::vector<float> grid = {0.01f, 0.02f};
  for (int step = 1; step <= 19; ++step) grid.push_back(0.05f * step);
  for (float threshold : {0.97f, 0.98f, 0.99f, 0.995f, 0.999f}) {
    grid.push_back(threshold);
  }
  for (const float threshold : grid) {
    double sum_f = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
      sum_f +=
          ScorePairSet(PairsAtThreshold(candidates[s], threshold), scenes[s])
              .f_measure;
    }
    const double mean_f = sum_f / scenes.size();
    if (mean_f >= best_f) {
      best_f = mean_f;
      best_threshold = threshold;
    }
  }
  return best_threshold;
}

std::vector<std::pair<int, int>> GcnRetrievedPairs(
    const GcnModel& model, const GcnTrainingScene& scene, int num_threads) {
  return PairsAtThreshold(GcnCandidatePairs(model, scene, num_threads),
                          model.info.threshold);
}

}  // namespace colmap_gcn

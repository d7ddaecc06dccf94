#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "evaluation/pair_set_score.h"
#include "gcn/gcn_model.h"
#include "retrieval/knn.h"
#include "training/gcn_training_samples.h"

namespace colmap_gcn {

// The scene's labels (positive_pairs matchable, unrelated_pairs wrong, pairs
// across part_of_row's parts cross-scene) of row pairs, every row labelled.
PairSetScore ScorePairSet(const std::vector<std::pair<int, int>>& pairs,
                          const GcnTrainingScene& scene);

// The fixed-k retrieval baseline at an equal number of pairs: the
// `num_pairs` most similar unordered pairs (ties by index).
std::vector<std::pair<int, int>> MostSimilarPairs(
    const EmbeddingMatrix& embeddings, size_t num_pairs);

// The shortest prefix of `ranked` holding num_true_positives matchable pairs
// of the scene (all of `ranked` if it holds fewer): a ranking's cost, in
// pairs, of reaching a given recall.
std::vector<std::pair<int, int>> ShortestPrefixWithTruePositives(
    std::vector<std::pair<int, int>> ranked,
    const GcnTrainingScene& scene,
    size_t num_true_positives);

// The highest precision of any prefix of `ranked` (best first; a repeated
// pair counts at its first place) whose recall over all of the scene's
// matchable pairs is at least `min_recall`, or -1 if no prefix reaches it.
// With the labels choosing the cut, this bounds what any threshold on the
// ranking can reach.
double BestPrecisionAtRecall(const std::vector<std::pair<int, int>>& ranked,
                             const GcnTrainingScene& scene,
                             double min_recall);

// The fixed-k retrieval baseline (paper's "CNN kNN"): the union of every
// image's k most similar images, as KnnPairGenerator selects them.
std::vector<std::pair<int, int>> TopKPairs(const EmbeddingMatrix& embeddings,
                                           int k,
                                           int num_threads);
// The same from a kNN graph with at least k neighbours per row (its first k
// columns), so several k share one search.
std::vector<std::pair<int, int>> TopKPairs(const KnnGraph& graph, int k);

// Every candidate pair of the GCN (1-hop nodes of all QESs, the model's
// recommended k1, k2, u) with its score, the max over both directions.
struct ScoredRowPair {
  int row1 = 0;
  int row2 = 0;
  float score = 0.f;
};
std::vector<ScoredRowPair> GcnCandidatePairs(const GcnModel& model,
                                             const GcnTrainingScene& scene,
                                             int num_threads);

// 1 for the candidates that are matchable pairs of the scene, else 0 (for
// AveragePrecision over the candidates).
std::vector<uint8_t> MatchableFlags(
    const std::vector<ScoredRowPair>& candidates,
    const GcnTrainingScene& scene);

// The candidates a threshold keeps (as GcnPairGenerator does).
std::vector<std::pair<int, int>> PairsAtThreshold(
    const std::vector<ScoredRowPair>& candidates, float threshold);

// The threshold in {0.01, 0.02, 0.05, 0.10, ..., 0.95, 0.97, 0.98, 0.99,
// 0.995, 0.999} maximising the mean pair-set F over the scenes (ties: the
// higher threshold, fewer pairs).
float SelectGcnThreshold(const GcnModel& model,
                         const std::vector<GcnTrainingScene>& scenes,
                         int num_threads);

// The pairs the GCN retrieves for a scene (GcnPairGenerator with the model's
// recommended settings, threshold only, no min_pairs_per_image fallback).
std::vector<std::pair<int, int>> GcnRetrievedPairs(
    const GcnModel& model, const GcnTrainingScene& scene, int num_threads);

}  // namespace colmap_gcn

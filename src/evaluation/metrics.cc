#include "evaluation/metrics.h"

#include <algorithm>
#include <set>

namespace colmap_gcn {

RetrievalMetrics ComputeRetrievalMetrics(
    const std::vector<ImageNamePair>& pairs,
    const PairLabels& labels,
    const PairLabelOptions& options) {
  RetrievalMetrics metrics;
  std::set<ImageNamePair> distinct;
  for (const auto& [name1, name2] : pairs) {
    if (name1 == name2) continue;
    distinct.emplace(std::min(name1, name2), std::max(name1, name2));
  }
  metrics.num_pairs = distinct.size();
  for (const auto& [name1, name2] : distinct) {
    if (!labels.IsLabelled(name1, name2)) continue;
    ++metrics.num_labelled_pairs;
    if (labels.IsMatchable(name1, name2, options)) {
      ++metrics.num_true_positives;
    }
    if (labels.SharesNothing(name1, name2)) ++metrics.num_wrong_pairs;
  }
  metrics.num_matchable = labels.MatchablePairs(options).size();
  const PrecisionRecall scores =
      ComputePrecisionRecall(metrics.num_true_positives,
                             metrics.num_labelled_pairs,
                             metrics.num_matchable);
  metrics.precision = scores.precision;
  metrics.recall = scores.recall;
  metrics.f_measure = scores.f_measure;
  return metrics;
}

RetrievalMetrics AverageRetrievalMetrics(
    const std::vector<RetrievalMetrics>& per_scene) {
  RetrievalMetrics average;
  if (per_scene.empty()) return average;
  for (const RetrievalMetrics& metrics : per_scene) {
    average.num_pairs += metrics.num_pairs;
    average.num_labelled_pairs += metrics.num_labelled_pairs;
    average.num_matchable += metrics.num_matchable;
    average.num_true_positives += metrics.num_true_positives;
    average.num_wrong_pairs += metrics.num_wrong_pairs;
    average.precision += metrics.precision;
    average.recall += metrics.recall;
    average.f_measure += metrics.f_measure;
  }
  average.precision /= per_scene.size();
  average.recall /= per_scene.size();
  average.f_measure /= per_scene.size();
  return average;
}

}  // namespace colmap_gcn

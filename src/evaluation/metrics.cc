#include "evaluation/metrics.h"

namespace colmap_gcn {

PairSetScore ComputeRetrievalMetrics(const std::vector<ImageNamePair>& pairs,
                                     const PairLabels& labels,
                                     const PairLabelOptions& options) {
  return ScorePairSet(pairs,
                      labels.MatchablePairs(options).size(),
                      [&](const std::string& name1, const std::string& name2) {
                        PairLabel label;
                        label.labelled = labels.IsLabelled(name1, name2);
                        if (!label.labelled) return label;
                        label.matchable =
                            labels.IsMatchable(name1, name2, options);
                        label.wrong = labels.SharesNothing(name1, name2);
                        return label;
                      });
}

PairSetScore AverageRetrievalMetrics(
    const std::vector<PairSetScore>& per_scene) {
  PairSetScore average;
  if (per_scene.empty()) return average;
  for (const PairSetScore& metrics : per_scene) {
    average.num_pairs += metrics.num_pairs;
    average.num_labelled_pairs += metrics.num_labelled_pairs;
    average.num_matchable += metrics.num_matchable;
    average.num_true_positives += metrics.num_true_positives;
    average.num_wrong_pairs += metrics.num_wrong_pairs;
    average.num_cross_scene += metrics.num_cross_scene;
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

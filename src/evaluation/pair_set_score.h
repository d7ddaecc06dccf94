#pragma once

#include <algorithm>
#include <cstddef>
#include <set>
#include <utility>
#include <vector>

#include "math/precision_recall.h"

namespace colmap_gcn {

// Retrieval quality of a pair set against labelled pairs: the one score of
// a pair set, for name pairs against ground-truth labels (benchmark, report)
// and for row pairs of a training scene (gcn_train, gcn_model_evaluator).
struct PairSetScore {
  size_t num_pairs = 0;           // distinct selected pairs
  size_t num_labelled_pairs = 0;  // of those, both images labelled
  size_t num_matchable = 0;       // labelled matchable pairs in the scene
  size_t num_true_positives = 0;  // selected and matchable
  size_t num_wrong_pairs = 0;     // selected, sharing nothing at all
  // Selected pairs across the parts of a collection (unrelated photos); 0
  // when the labels do not know the parts.
  size_t num_cross_scene = 0;
  double precision = 0;  // true positives / labelled selected pairs
  double recall = 0;     // true positives / matchable pairs
  double f_measure = 0;  // harmonic mean; 0 when both are 0
};

// What the labels say of one selected pair.
struct PairLabel {
  bool labelled = true;  // false: left out of precision and wrong pairs
  bool matchable = false;
  bool wrong = false;  // the images share nothing at all
  bool cross_scene = false;
};

// Sets precision, recall and F from the counts.
void FinishPairSetScore(PairSetScore* score);

// Scores `pairs` (self-pairs dropped, each unordered pair once, whatever its
// order or repeats) against `num_matchable` matchable pairs, label(a, b)
// (a < b) labelling each distinct pair.
template <typename Id, typename LabelPair>
PairSetScore ScorePairSet(const std::vector<std::pair<Id, Id>>& pairs,
                          size_t num_matchable,
                          const LabelPair& label) {
  std::set<std::pair<Id, Id>> distinct;
  for (const auto& [a, b] : pairs) {
    if (a != b) distinct.emplace(std::min(a, b), std::max(a, b));
  }
  PairSetScore score;
  score.num_pairs = distinct.size();
  score.num_matchable = num_matchable;
  for (const auto& [a, b] : distinct) {
    const PairLabel pair_label = label(a, b);
    if (!pair_label.labelled) continue;
    ++score.num_labelled_pairs;
    score.num_true_positives += pair_label.matchable;
    score.num_wrong_pairs += pair_label.wrong;
    score.num_cross_scene += pair_label.cross_scene;
  }
  FinishPairSetScore(&score);
  return score;
}

}  // namespace colmap_gcn

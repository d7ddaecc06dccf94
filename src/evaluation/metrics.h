#pragma once

#include <vector>

#include "evaluation/labels.h"
#include "math/precision_recall.h"
#include "pairing/pairs_io.h"

namespace colmap_gcn {

// A method's pair set against the labels (paper Tables 1-2).
struct RetrievalMetrics {
  size_t num_pairs = 0;           // distinct attempted pairs
  size_t num_labelled_pairs = 0;  // of those, both images labelled
  size_t num_matchable = 0;       // labelled matchable pairs in the scene
  size_t num_true_positives = 0;  // attempted and matchable
  size_t num_wrong_pairs = 0;     // attempted, sharing nothing at all
  double precision = 0;           // true positives / labelled attempted pairs
  double recall = 0;              // true positives / matchable pairs
  double f_measure = 0;           // harmonic mean; 0 when both are 0
};

// Self-pairs and repeated pairs (either order) count once; pairs with an
// unlabelled image are left out of precision and wrong pairs.
RetrievalMetrics ComputeRetrievalMetrics(
    const std::vector<ImageNamePair>& pairs,
    const PairLabels& labels,
    const PairLabelOptions& options);

// Scene average as in the paper's tables: precision, recall and F-measure
// are means over scenes (not pooled), counts are sums.
RetrievalMetrics AverageRetrievalMetrics(
    const std::vector<RetrievalMetrics>& per_scene);

}  // namespace colmap_gcn

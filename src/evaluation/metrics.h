#pragma once

#include <vector>

#include "evaluation/labels.h"
#include "evaluation/pair_set_score.h"
#include "pairing/pairs_io.h"

namespace colmap_gcn {

// A method's pair set against the labels (paper Tables 1-2), scored by
// ScorePairSet: self-pairs and repeated pairs (either order) count once;
// pairs with an unlabelled image are left out of precision and wrong pairs.
PairSetScore ComputeRetrievalMetrics(const std::vector<ImageNamePair>& pairs,
                                     const PairLabels& labels,
                                     const PairLabelOptions& options);

// Scene average as in the paper's tables: precision, recall and F-measure
// are means over scenes (not pooled), counts are sums.
PairSetScore AverageRetrievalMetrics(
    const std::vector<PairSetScore>& per_scene);

}  // namespace colmap_gcn

#include "evaluation/pair_set_score.h"

namespace colmap_gcn {

void FinishPairSetScore(PairSetScore* score) {
  const PrecisionRecall scores =
      ComputePrecisionRecall(score->num_true_positives,
                             score->num_labelled_pairs,
                             score->num_matchable);
  score->precision = scores.precision;
  score->recall = scores.recall;
  score->f_measure = scores.f_measure;
}

}  // namespace colmap_gcn

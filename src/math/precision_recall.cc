#include "math/precision_recall.h"

namespace colmap_gcn {

PrecisionRecall ComputePrecisionRecall(const size_t num_true_positives,
                                       const size_t num_selected,
                                       const size_t num_relevant) {
  PrecisionRecall scores;
  if (num_selected > 0) {
    scores.precision = static_cast<double>(num_true_positives) / num_selected;
  }
  if (num_relevant > 0) {
    scores.recall = static_cast<double>(num_true_positives) / num_relevant;
  }
  scores.f_measure = FMeasure(scores.precision, scores.recall);
  return scores;
}

double FMeasure(const double precision, const double recall) {
  return precision + recall <= 0
             ? 0.0
             : 2.0 * precision * recall / (precision + recall);
}

}  // namespace colmap_gcn

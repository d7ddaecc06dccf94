#pragma once

#include <cstddef>

namespace colmap_gcn {

// Retrieval quality of a selected set against the relevant items.
struct PrecisionRecall {
  double precision = 0;  // true positives / selected; 0 when none selected
  double recall = 0;     // true positives / relevant; 0 when none relevant
  double f_measure = 0;  // harmonic mean; 0 when both are 0
};

PrecisionRecall ComputePrecisionRecall(size_t num_true_positives,
                                       size_t num_selected,
                                       size_t num_relevant);

// Harmonic mean of precision and recall; 0 when both are 0.
double FMeasure(double precision, double recall);

}  // namespace colmap_gcn

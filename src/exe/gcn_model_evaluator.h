#pragma once

namespace colmap_gcn {

// `colmap gcn_model_evaluator`: a model against fixed-k retrieval on
// labelled scenes it was not trained on, and its parameter sensitivity
// (k1, k2, u, threshold) as CSV and plots.
int RunGcnModelEvaluator(int argc, char** argv);

}  // namespace colmap_gcn

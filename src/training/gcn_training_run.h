#pragma once

#include <string>
#include <vector>

#include "gcn/gcn_model.h"
#include "training/gcn_training.h"
#include "training/model_evaluation.h"

namespace colmap_gcn {

// What `colmap gcn_train` does, its flags parsed: the scenes of a
// gcn_benchmark output folder, held-out scenes set aside, the model
// trained and written, and compared with fixed-k retrieval on the test
// scenes.
struct GcnTrainingRunOptions {
  // gcn_benchmark output folder with the labelled scenes.
  std::string benchmark_path;
  // The model file written.
  std::string output_path;
  // Training scenes ("a+b": a collection of scenes a and b); empty: all
  // scenes but the validation and test scenes.
  std::vector<std::string> scenes;
  // For early stopping and the threshold; empty: held-out queries.
  std::vector<std::string> validation_scenes;
  // Held out entirely; the model is compared with fixed-k retrieval on them.
  std::vector<std::string> test_scenes;
  // The largest per-image k of the fixed-k baselines (the paper's k range).
  int max_fixed_k = 100;
  GcnTrainingPipelineOptions pipeline;
};

struct GcnTrainingRun {
  GcnModel model;
  // Training and writing the model.
  double seconds = 0;
  // One per test scene (empty without test scenes).
  std::vector<FixedKComparison> test_comparisons;
};

// Throws Error when no training scene is left or a named scene is missing.
GcnTrainingRun RunGcnTraining(const GcnTrainingRunOptions& options);

}  // namespace colmap_gcn

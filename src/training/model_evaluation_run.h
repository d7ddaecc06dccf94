#pragma once

#include <string>
#include <vector>

#include "gcn/gcn_model.h"
#include "training/model_evaluation.h"

namespace colmap_gcn {

// What `colmap gcn_model_evaluator` does, its flags parsed: models compared
// with fixed-k retrieval on labelled scenes they were not trained on, in
// one table, and optionally one model's k1/k2/u/threshold sensitivity.
struct GcnModelEvaluationOptions {
  // gcn_benchmark output folder with the labelled scenes.
  std::string benchmark_path;
  // One fold per model and its held-out scenes (an empty scene list: every
  // labelled scene; an empty model path: the default model).
  std::vector<EvaluationFold> folds;
  // Markdown file for the table; empty: none.
  std::string output_path = "";
  // Folder for sensitivity.csv and plots (of the last fold's model on its
  // scenes); empty: no sweep.
  std::string sensitivity_path = "";
  // Largest per-image k compared.
  int max_k = 100;
  // Label thresholds; < 0: each model's training ones.
  double tau_mo = -1;
  double tau_ct = -1;
  // The ONNX network of a CNN-embedding model, and where its images are.
  std::string onnx_path = "";
  SceneImageOptions images;
  // -1: all cores.
  int num_threads = -1;
};

struct EvaluatedGcnModel {
  std::string model_path;
  GcnModelInfo info;
  std::vector<std::string> scenes;
};

struct GcnModelEvaluation {
  // Each fold's model, in order.
  std::vector<EvaluatedGcnModel> models;
  // FormatFixedKComparison of every fold's scenes.
  std::string table;
  // With options.sensitivity_path: the sweep of the last fold's model,
  // averaged over its scenes.
  std::vector<GcnSensitivityPoint> sensitivity;
  size_t num_sensitivity_scenes = 0;
};

// Writes options.output_path and the sensitivity files when set; throws
// Error naming a missing model, scene or an unwritable file.
GcnModelEvaluation EvaluateGcnModels(const GcnModelEvaluationOptions& options);

}  // namespace colmap_gcn

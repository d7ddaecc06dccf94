#include "training/model_evaluation_run.h"

#include <fstream>

#include "gcn/model_file.h"
#include "pairing/gcn_model_pairing.h"
#include "util/error.h"

namespace colmap_gcn {

GcnModelEvaluation EvaluateGcnModels(const GcnModelEvaluationOptions& options) {
  GcnModelEvaluation evaluation;
  // Each fold's scenes embedded and compared with the fold's own model.
  std::vector<FixedKComparison> comparisons;
  std::vector<GcnTrainingScene> embedded;
  GcnModel model;
  for (const auto& fold : options.folds) {
    const std::string model_path =
        fold.model_path.empty() ? DefaultGcnModelPath() : fold.model_path;
    model = ReadGcnModel(model_path);
    PairLabelOptions labels;
    labels.min_overlap =
        options.tau_mo < 0 ? model.info.tau_mo : options.tau_mo;
    labels.min_common_track_ratio =
        options.tau_ct < 0 ? model.info.tau_ct : options.tau_ct;
    labels.Check();
    embedded = EmbedScenesForModel(
        model,
        FindLabelledScenes(options.benchmark_path, fold.scenes),
        labels,
        options.num_threads,
        options.onnx_path,
        options.images);
    const std::vector<FixedKComparison> fold_comparisons =
        CompareWithFixedK(model, embedded, options.max_k, options.num_threads);
    comparisons.insert(
        comparisons.end(), fold_comparisons.begin(), fold_comparisons.end());
    evaluation.models.push_back({model_path, model.info, fold.scenes});
  }
  evaluation.table = FormatFixedKComparison(comparisons);
  if (!options.output_path.empty()) {
    std::ofstream file(options.output_path);
    file << evaluation.table;
    if (!file) ThrowError("cannot write ", options.output_path);
  }
  if (!options.sensitivity_path.empty()) {
    GcnSensitivityOptions sensitivity;
    sensitivity.num_threads = options.num_threads;
    evaluation.sensitivity =
        ComputeGcnSensitivity(model, embedded, sensitivity);
    evaluation.num_sensitivity_scenes = embedded.size();
    WriteGcnSensitivity(
        evaluation.sensitivity,
        "mean over " + std::to_string(embedded.size()) + " held-out scenes",
        options.sensitivity_path);
  }
  return evaluation;
}

}  // namespace colmap_gcn

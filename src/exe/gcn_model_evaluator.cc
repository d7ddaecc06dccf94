#include "exe/gcn_model_evaluator.h"

#include <cstdio>

#include "training/model_evaluation_run.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {
namespace {

void PrintSensitivity(const GcnModelEvaluation& evaluation,
                      const std::string& sensitivity_path) {
  const GcnModelInfo& info = evaluation.models.back().info;
  std::printf(
      "\nsensitivity (mean over scenes; others at k1 %d, k2 %d, "
      "u %d, threshold %.2f)\n%-10s %6s %6s %6s %6s %8s\n",
      info.test_k1,
      info.test_k2,
      info.test_u,
      info.threshold,
      "parameter",
      "value",
      "P",
      "R",
      "F",
      "pairs/im");
  for (const auto& point : evaluation.sensitivity) {
    std::printf("%-10s %6g %6.3f %6.3f %6.3f %8.2f\n",
                point.parameter.c_str(),
                point.value,
                point.precision,
                point.recall,
                point.f,
                point.pairs_per_image);
  }
  std::printf("wrote %s/sensitivity.csv and sensitivity_*.png\n",
              sensitivity_path.c_str());
}

}  // namespace

int RunGcnModelEvaluator(int argc, char** argv) {
  GcnModelEvaluationOptions options;
  std::string scenes;
  std::string model_path;
  std::string folds_path;
  OptionManager manager(
      "gcn_model_evaluator",
      "Compares a GCN model with fixed-k retrieval on labelled scenes "
      "prepared by `colmap gcn_benchmark` (e.g. --methods none) and, with "
      "--sensitivity_path, sweeps k1, k2, u and the threshold. Never "
      "evaluate on scenes the model was trained on.");
  manager.AddRequiredOption("benchmark_path",
                            &options.benchmark_path,
                            "gcn_benchmark output folder with the scenes");
  manager.AddDefaultOption(
      "scenes",
      &scenes,
      "comma list (a+b: a collection of scenes a and b, pairs across them "
      "unrelated); empty: every labelled scene");
  manager.AddDefaultOption(
      "model_path", &model_path, "empty: the default model");
  manager.AddDefaultOption("output_path",
                           &options.output_path,
                           "markdown file for the table (optional)");
  manager.AddDefaultOption(
      "folds_path",
      &folds_path,
      "leave-scene-out folds instead of --model_path/--scenes: lines "
      "\"<model path> <scene>[,<scene>...]\", each scene evaluated by its "
      "line's model, all in one table");
  manager.AddDefaultOption("sensitivity_path",
                           &options.sensitivity_path,
                           "folder for sensitivity.csv and plots (optional)");
  manager.AddDefaultOption(
      "max_k", &options.max_k, "largest per-image k compared");
  manager.AddDefaultOption("tau_mo",
                           &options.tau_mo,
                           "label thresholds; < 0: the model's training ones");
  manager.AddDefaultOption("tau_ct", &options.tau_ct);
  manager.AddDefaultOption(
      "num_threads", &options.num_threads, "-1: all cores");
  manager.AddDefaultOption("onnx_path",
                           &options.onnx_path,
                           "the ONNX network of a CNN-embedding model");
  manager.AddDefaultOption("image_root",
                           &options.images.image_root,
                           "folder with <scene>/images (CNN models)");
  manager.AddDefaultOption(
      "onnx_cache_dir",
      &options.images.cnn_cache_dir,
      "CNN descriptor caches; empty: beside each scene's base.db");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] {
    const int& max_k = options.max_k;
    const double& tau_mo = options.tau_mo;
    const double& tau_ct = options.tau_ct;
    const int& num_threads = options.num_threads;
    CHECK_OPTION_GE(max_k, 1);
    CHECK_OPTION(tau_mo,
                 tau_mo < 0 || (tau_mo > 0 && tau_mo <= 1),
                 "be < 0 (the model's value) or in (0, 1]");
    CHECK_OPTION(tau_ct,
                 tau_ct < 0 || (tau_ct > 0 && tau_ct <= 1),
                 "be < 0 (the model's value) or in (0, 1]");
    CHECK_OPTION_NUM_THREADS(num_threads);
  });
  manager.Check([&] {
    const std::string& sensitivity_path = options.sensitivity_path;
    CHECK_OPTION(folds_path,
                 folds_path.empty() || (model_path.empty() && scenes.empty()),
                 "not be combined with --model_path or --scenes");
    CHECK_OPTION(sensitivity_path,
                 sensitivity_path.empty() || folds_path.empty(),
                 "not be combined with --folds_path");
  });
  options.folds =
      folds_path.empty()
          ? std::vector<EvaluationFold>{{model_path, SplitCommaList(scenes)}}
          : ReadEvaluationFolds(folds_path);

  const GcnModelEvaluation evaluation = EvaluateGcnModels(options);
  for (const EvaluatedGcnModel& model : evaluation.models) {
    std::printf("model %s (k1 %d, k2 %d, u %d, threshold %.2f): %s\n",
                model.model_path.c_str(),
                model.info.test_k1,
                model.info.test_k2,
                model.info.test_u,
                model.info.threshold,
                StringJoin(model.scenes, ",").c_str());
  }
  std::printf("\n%s", evaluation.table.c_str());
  if (!options.sensitivity_path.empty()) {
    PrintSensitivity(evaluation, options.sensitivity_path);
  }
  return 0;
}

}  // namespace colmap_gcn

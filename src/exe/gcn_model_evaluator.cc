#include "exe/gcn_model_evaluator.h"

#include <cstdio>
#include <fstream>

#include "controllers/gcn_model_pairing.h"
#include "gcn/model_file.h"
#include "training/model_evaluation.h"
#include "util/error.h"
#include "util/file.h"
#include "util/option_check.h"
#include "util/option_manager.h"
#include "util/string.h"

namespace colmap_gcn {

int RunGcnModelEvaluator(int argc, char** argv) {
  std::string benchmark_path;
  std::string scenes;
  std::string model_path;
  std::string output_path;
  std::string sensitivity_path;
  std::string folds_path;
  double tau_mo = -1;
  double tau_ct = -1;
  int max_k = 100;
  int num_threads = -1;
  std::string onnx_path;
  SceneImageOptions images;
  OptionManager manager(
      "gcn_model_evaluator",
      "Compares a GCN model with fixed-k retrieval on labelled scenes "
      "prepared by `colmap gcn_benchmark` (e.g. --methods none) and, with "
      "--sensitivity_path, sweeps k1, k2, u and the threshold. Never "
      "evaluate on scenes the model was trained on.");
  manager.AddRequiredOption("benchmark_path",
                            &benchmark_path,
                            "gcn_benchmark output folder with the scenes");
  manager.AddDefaultOption(
      "scenes",
      &scenes,
      "comma list (a+b: a collection of scenes a and b, pairs across them "
      "unrelated); empty: every labelled scene");
  manager.AddDefaultOption(
      "model_path", &model_path, "empty: the default model");
  manager.AddDefaultOption(
      "output_path", &output_path, "markdown file for the table (optional)");
  manager.AddDefaultOption(
      "folds_path",
      &folds_path,
      "leave-scene-out folds instead of --model_path/--scenes: lines "
      "\"<model path> <scene>[,<scene>...]\", each scene evaluated by its "
      "line's model, all in one table");
  manager.AddDefaultOption("sensitivity_path",
                           &sensitivity_path,
                           "folder for sensitivity.csv and plots (optional)");
  manager.AddDefaultOption("max_k", &max_k, "largest per-image k compared");
  manager.AddDefaultOption(
      "tau_mo", &tau_mo, "label thresholds; < 0: the model's training ones");
  manager.AddDefaultOption("tau_ct", &tau_ct);
  manager.AddDefaultOption("num_threads", &num_threads, "-1: all cores");
  manager.AddDefaultOption(
      "onnx_path", &onnx_path, "the ONNX network of a CNN-embedding model");
  manager.AddDefaultOption("image_root",
                           &images.image_root,
                           "folder with <scene>/images (CNN models)");
  manager.AddDefaultOption(
      "onnx_cache_dir",
      &images.cnn_cache_dir,
      "CNN descriptor caches; empty: beside each scene's base.db");
  if (!manager.Parse(argc, argv)) {
    return 0;
  }
  manager.Check([&] {
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
    CHECK_OPTION(folds_path,
                 folds_path.empty() || (model_path.empty() && scenes.empty()),
                 "not be combined with --model_path or --scenes");
    CHECK_OPTION(sensitivity_path,
                 sensitivity_path.empty() || folds_path.empty(),
                 "not be combined with --folds_path");
  });
  std::vector<EvaluationFold> folds;
  if (folds_path.empty()) {
    folds.push_back({model_path.empty() ? DefaultGcnModelPath() : model_path,
                     SplitCommaList(scenes)});
  } else {
    folds = ReadEvaluationFolds(folds_path);
  }
  // Each fold's scenes embedded and compared with the fold's own model.
  std::vector<FixedKComparison> comparisons;
  std::vector<GcnTrainingScene> embedded;
  GcnModel model;
  for (const auto& fold : folds) {
    model = ReadGcnModel(fold.model_path);
    PairLabelOptions labels;
    labels.min_overlap = tau_mo < 0 ? model.info.tau_mo : tau_mo;
    labels.min_common_track_ratio = tau_ct < 0 ? model.info.tau_ct : tau_ct;
    labels.Check();
    embedded =
        EmbedScenesForModel(model,
                            FindLabelledScenes(benchmark_path, fold.scenes),
                            labels,
                            num_threads,
                            onnx_path,
                            images);
    const std::vector<FixedKComparison> fold_comparisons =
        CompareWithFixedK(model, embedded, max_k, num_threads);
    comparisons.insert(
        comparisons.end(), fold_comparisons.begin(), fold_comparisons.end());
    std::printf("model %s (k1 %d, k2 %d, u %d, threshold %.2f): %s\n",
                fold.model_path.c_str(),
                model.info.test_k1,
                model.info.test_k2,
                model.info.test_u,
                model.info.threshold,
                StringJoin(fold.scenes, ",").c_str());
  }
  const std::string table = FormatFixedKComparison(comparisons);
  std::printf("\n%s", table.c_str());
  if (!output_path.empty()) {
    std::ofstream file(output_path);
    file << table;
    if (!file) ThrowError("cannot write ", output_path);
  }
  if (!sensitivity_path.empty()) {
    GcnSensitivityOptions options;
    options.num_threads = num_threads;
    const auto points = ComputeGcnSensitivity(model, embedded, options);
    WriteGcnSensitivity(
        points,
        "mean over " + std::to_string(embedded.size()) + " held-out scenes",
        sensitivity_path);
    std::printf(
        "\nsensitivity (mean over scenes; others at k1 %d, k2 %d, "
        "u %d, threshold %.2f)\n%-10s %6s %6s %6s %6s %8s\n",
        model.info.test_k1,
        model.info.test_k2,
        model.info.test_u,
        model.info.threshold,
        "parameter",
        "value",
        "P",
        "R",
        "F",
        "pairs/im");
    for (const auto& point : points) {
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
  return 0;
}

}  // namespace colmap_gcn

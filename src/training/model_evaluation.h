#pragma once

#include <string>
#include <vector>

#include "gcn/gcn_model.h"
#include "training/gcn_training.h"

namespace colmap_gcn {

// The labelled scenes embedded with the model's own embedding (VLAD, CNN
// or both; throws Error for models on imported descriptors). CNN models
// need the ONNX network (onnx_path; `onnx_flag` names its option in
// errors) and the scenes' images.
std::vector<GcnTrainingScene> EmbedScenesForModel(
    const GcnModel& model,
    const std::vector<LabelledScene>& scenes,
    const PairLabelOptions& label_options,
    int num_threads,
    const std::string& onnx_path = "",
    const SceneImageOptions& images = SceneImageOptions(),
    const std::string& onnx_flag = "--onnx_path");

// A model against fixed-k retrieval on the same embedding, on one scene
// the model was not trained on.
struct FixedKComparison {
  std::string scene;
  size_t num_unrelated_pairs = 0;  // the scene's pairs that share nothing
  int num_images = 0;
  bool is_collection = false;  // a collection of scenes ("a+b")
  float threshold = 0.5f;      // the model's decision threshold
  // The GCN's distinct candidate pairs (1-hop nodes of every QES): what a
  // kNN with k = k1 would match; gcn.num_pairs of them are kept.
  size_t num_candidates = 0;
  double KeptFraction() const;
  PairSetScore gcn;    // the model's recommended settings and threshold
  PairSetScore equal;  // the gcn.num_pairs most similar pairs
  // The fewest most-similar-first pairs with at least the GCN's true
  // positives (kNN at equal recall): its num_unrelated against the GCN's
  // is the wrong-pair comparison of ambiguous scenes.
  PairSetScore equal_recall;
  int equal_k = 0;  // smallest per-image k giving >= gcn.num_pairs
  PairSetScore top_k_equal;
  int best_k = 0;  // per-image k in [1, max_k] with the best F
  PairSetScore top_k_best;
  // Ranking of the GCN's candidate pairs (the 1-hop nodes of every QES):
  // average precision by GCN score and by embedding similarity.
  double gcn_ap = 0;
  double similarity_ap = 0;
  // The best precision any threshold reaches at recall >=
  // kPrecisionAtRecall (chosen with the labels): by GCN score over the
  // candidates and by similarity over all pairs; -1 where the ranking
  // never reaches that recall.
  double gcn_precision_at_recall = -1;
  double similarity_precision_at_recall = -1;
};

// Recall at which FixedKComparison reports the best reachable precision
// (the retrieval target on real scenes: P >= 0.85 at R >= 0.8).
constexpr double kPrecisionAtRecall = 0.8;
constexpr double kTargetPrecision = 0.85;

FixedKComparison CompareWithFixedK(const GcnModel& model,
                                   const GcnTrainingScene& scene,
                                   int max_k,
                                   int num_threads);

// ... for each scene.
std::vector<FixedKComparison> CompareWithFixedK(
    const GcnModel& model,
    const std::vector<GcnTrainingScene>& scenes,
    int max_k,
    int num_threads);

// The comparison as markdown: the F/AP table with a mean row, then the
// wrong pairs of the GCN and of kNN at equal recall (scenes whose labels
// mark pairs that share nothing). Each row carries its own model's
// threshold, so comparisons of several models (leave-scene-out folds) form
// one table.
std::string FormatFixedKComparison(
    const std::vector<FixedKComparison>& comparisons);

// One model and the scenes it is evaluated on (a leave-scene-out fold).
struct EvaluationFold {
  std::string model_path;
  std::vector<std::string> scenes;
};

// Folds file: one fold per line, "<model path> <scene>[,<scene>...]";
// blank lines and lines starting with # are skipped. Throws Error naming
// the line of a malformed entry or a scene listed twice.
std::vector<EvaluationFold> ReadEvaluationFolds(const std::string& path);

// Parameter sensitivity like the paper's Fig. 7: one of k1, k2, u and the
// decision threshold varied at a time from the model's recommended
// settings; precision, recall and F averaged over scenes.
struct GcnSensitivityOptions {
  std::vector<int> k1_values = {5, 10, 20, 30, 40, 60, 80, 100};
  std::vector<int> k2_values = {1, 2, 3, 5, 8, 10};
  std::vector<int> u_values = {1, 2, 3, 5, 8, 10};
  std::vector<double> thresholds = {
      0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95};
  int num_threads = -1;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

struct GcnSensitivityPoint {
  std::string parameter;  // k1 | k2 | u | threshold
  double value = 0;
  double precision = 0;
  double recall = 0;
  double f = 0;
  double pairs_per_image = 0;
};

std::vector<GcnSensitivityPoint> ComputeGcnSensitivity(
    const GcnModel& model,
    const std::vector<GcnTrainingScene>& scenes,
    const GcnSensitivityOptions& options);

// <dir>/sensitivity.csv and one plot per parameter,
// <dir>/sensitivity_<parameter>.png (precision, recall, F).
void WriteGcnSensitivity(const std::vector<GcnSensitivityPoint>& points,
                         const std::string& title,
                         const std::string& dir);

}  // namespace colmap_gcn

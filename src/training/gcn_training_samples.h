#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "gcn/gcn_model.h"
#include "gcn/query_enclosing_subgraph.h"
#include "math/precision_recall.h"
#include "retrieval/knn.h"
#include "training/gcn_network.h"

namespace colmap_gcn {

// One training collection, decoupled from databases: embeddings (rows =
// images, L2-normalised) and the matchable pairs (unordered row-index pairs;
// e.g. MO >= tau_MO or CT >= tau_CT). Every other pair is a negative.
struct GcnTrainingScene {
  std::string name;
  EmbeddingMatrix embeddings;
  std::vector<std::pair<int, int>> positive_pairs;
  // Labelled pairs whose images share nothing (no surface, no 3D point): a
  // match between them can only be wrong. Evaluation only; may be empty.
  std::vector<std::pair<int, int>> unrelated_pairs;
  // A collection of scenes ("a+b"): the part each row comes from, so pairs
  // across parts can be counted. Empty for a single scene.
  std::vector<int> part_of_row;
};

struct GcnClassificationStats {
  double loss = 0;  // mean weighted BCE per 1-hop node
  int64_t num_nodes = 0;
  int64_t true_positives = 0;
  int64_t false_positives = 0;
  int64_t false_negatives = 0;
  // Average precision of each query's 1-hop nodes ranked by logit, summed
  // over the queries with at least one matchable node (threshold free).
  double average_precision_sum = 0;
  int64_t num_ranked_queries = 0;
  PrecisionRecall Scores() const;
  double Precision() const;
  double Recall() const;
  double F() const;
  double MeanAveragePrecision() const;
  // Adds the counts and loss sums of `other`.
  void Accumulate(const GcnClassificationStats& other);
  // "loss 0.1234 P 0.500 R 0.500 F 0.500 AP 0.500".
  std::string Format() const;
};

// Average precision of items ranked by score (highest first, ties in item
// order): the mean over relevant items of the precision at their rank; 0
// without relevant items. scores and relevant have the same size.
double AveragePrecision(const std::vector<float>& scores,
                        const std::vector<uint8_t>& relevant);

// A scene ready for sampling: its kNN graph for the (capped) QES and the
// positive pairs as keys.
struct PreparedTrainingScene {
  const GcnTrainingScene* scene = nullptr;
  KnnGraph knn;
  QesOptions qes;
  std::unordered_set<uint64_t> positives;

  bool IsPositive(int i, int j) const;
};

// Throws Error if the scene has fewer than 2 images or a positive pair
// outside them. `scene` must outlive the result.
PreparedTrainingScene PrepareTrainingScene(const GcnTrainingScene& scene,
                                           const QesOptions& qes,
                                           int num_threads);

// One QES of the training data: a query of a prepared scene.
struct TrainingSample {
  int scene;
  int query;
};

// Per-thread QES builders, one per scene, created on first use.
class QesBuilderPool {
 public:
  QesBuilderPool(const std::vector<PreparedTrainingScene>& scenes,
                 QesStructureFeatures structure,
                 int num_threads);
  QesBuilder& Get(int thread, int scene);

 private:
  const std::vector<PreparedTrainingScene>& scenes_;
  const QesStructureFeatures structure_;
  std::vector<std::vector<std::unique_ptr<QesBuilder>>> builders_;
};

// The network input of one sample with its 1-hop labels.
GcnGraph<float> MakeSampleGraph(const GcnModel& model,
                                const PreparedTrainingScene& scene,
                                int query,
                                QesBuilder* builder);

// Adds one sample's predictions at `threshold` and its average precision.
void AddPredictions(const ColVector<float>& logits,
                    const std::vector<uint8_t>& labels,
                    float threshold,
                    GcnClassificationStats* stats);

// The model on the samples, forward only; the loss is the mean over nodes.
GcnClassificationStats EvaluateSamples(
    const GcnModel& model,
    const std::vector<PreparedTrainingScene>& scenes,
    const std::vector<TrainingSample>& samples,
    float positive_weight,
    float threshold,
    int num_threads,
    QesBuilderPool* pool);

}  // namespace colmap_gcn

#include "training/gcn_training_samples.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "util/error.h"
#include "util/pair_key.h"
#include "util/threading.h"

namespace colmap_gcn {

PrecisionRecall GcnClassificationStats::Scores() const {
  return ComputePrecisionRecall(true_positives,
                                true_positives + false_positives,
                                true_positives + false_negatives);
}

double GcnClassificationStats::Precision() const { return Scores().precision; }

double GcnClassificationStats::Recall() const { return Scores().recall; }

double GcnClassificationStats::F() const { return Scores().f_measure; }

double GcnClassificationStats::MeanAveragePrecision() const {
  return num_ranked_queries > 0 ? average_precision_sum / num_ranked_queries
                                : 0.0;
}

void GcnClassificationStats::Accumulate(const GcnClassificationStats& other) {
  loss += other.loss;
  num_nodes += other.num_nodes;
  true_positives += other.true_positives;
  false_positives += other.false_positives;
  false_negatives += other.false_negatives;
  average_precision_sum += other.average_precision_sum;
  num_ranked_queries += other.num_ranked_queries;
}

std::string GcnClassificationStats::Format() const {
  char buffer[128];
  std::snprintf(buffer,
                sizeof(buffer),
                "loss %.4f P %.3f R %.3f F %.3f AP %.3f",
                loss,
                Precision(),
                Recall(),
                F(),
                MeanAveragePrecision());
  return buffer;
}

double AveragePrecision(const std::vector<float>& scores,
                        const std::vector<uint8_t>& relevant) {
  THROW_CHECK(scores.size() == relevant.size());
  std::vector<int> order(scores.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return scores[a] > scores[b];
  });
  int64_t hits = 0;
  double precision_sum = 0;
  for (size_t rank = 0; rank < order.size(); ++rank) {
    if (relevant[order[rank]]) {
      ++hits;
      precision_sum += static_cast<double>(hits) / (rank + 1);
    }
  }
  return hits > 0 ? precision_sum / hits : 0.0;
}

bool PreparedTrainingScene::IsPositive(int i, int j) const {
  return positives.count(PairKey(i, j)) > 0;
}

PreparedTrainingScene PrepareTrainingScene(const GcnTrainingScene& scene,
                                           const QesOptions& qes,
                                           int num_threads) {
  const int n = static_cast<int>(scene.embeddings.rows());
  if (n < 2) {
    ThrowError("training scene '",
               scene.name,
               "' has ",
               n,
               " images; at least 2 are needed");
  }
  PreparedTrainingScene prepared;
  prepared.scene = &scene;
  prepared.qes = CapQesOptions(qes, n);
  prepared.knn = ComputeKnnForQes(scene.embeddings, prepared.qes, num_threads);
  for (const auto& [i, j] : scene.positive_pairs) {
    if (i < 0 || j < 0 || i >= n || j >= n) {
      ThrowError("training scene '",
                 scene.name,
                 "' has a positive pair (",
                 i,
                 ", ",
                 j,
                 ") outside its ",
                 n,
                 " images");
    }
    if (i == j) continue;
    prepared.positives.insert(PairKey(i, j));
  }
  return prepared;
}

QesBuilderPool::QesBuilderPool(const std::vector<PreparedTrainingScene>& scenes,
                               QesStructureFeatures structure,
                               int num_threads)
    : scenes_(scenes), structure_(structure), builders_(num_threads) {
  for (auto& per_thread : builders_) per_thread.resize(scenes.size());
}

QesBuilder& QesBuilderPool::Get(int thread, int scene) {
  auto& builder = builders_[thread][scene];
  if (!builder) {
    builder = std::make_unique<QesBuilder>(
        scenes_[scene].knn, scenes_[scene].qes, structure_);
  }
  return *builder;
}

GcnGraph<float> MakeSampleGraph(const GcnModel& model,
                                const PreparedTrainingScene& scene,
                                int query,
                                QesBuilder* builder) {
  QuerySubgraph subgraph;
  builder->Build(query, &subgraph);
  GcnGraph<float> graph =
      MakeGcnGraph(model, subgraph, scene.scene->embeddings);
  graph.labels.resize(subgraph.num_one_hop);
  for (int i = 0; i < subgraph.num_one_hop; ++i) {
    graph.labels[i] = scene.IsPositive(query, subgraph.nodes[i]) ? 1 : 0;
  }
  return graph;
}

void AddPredictions(const ColVector<float>& logits,
                    const std::vector<uint8_t>& labels,
                    float threshold,
                    GcnClassificationStats* stats) {
  for (int i = 0; i < logits.size(); ++i) {
    const float p = 1.f / (1.f + std::exp(-logits(i)));
    const bool predicted = p >= threshold;
    if (predicted && labels[i]) ++stats->true_positives;
    if (predicted && !labels[i]) ++stats->false_positives;
    if (!predicted && labels[i]) ++stats->false_negatives;
  }
  stats->num_nodes += logits.size();
  if (std::find(labels.begin(), labels.end(), 1) != labels.end()) {
    stats->average_precision_sum += AveragePrecision(
        std::vector<float>(logits.data(), logits.data() + logits.size()),
        labels);
    ++stats->num_ranked_queries;
  }
}

GcnClassificationStats EvaluateSamples(
    const GcnModel& model,
    const std::vector<PreparedTrainingScene>& scenes,
    const std::vector<TrainingSample>& samples,
    float positive_weight,
    float threshold,
    int num_threads,
    QesBuilderPool* pool) {
  std::vector<GcnClassificationStats> per_sample(samples.size());
  ParallelFor(
      0, static_cast<int>(samples.size()), num_threads, [&](int s, int thread) {
        const TrainingSample& sample = samples[s];
        const GcnGraph<float> graph =
            MakeSampleGraph(model,
                            scenes[sample.scene],
                            sample.query,
                            &pool->Get(thread, sample.scene));
        ColVector<float> logits;
        per_sample[s].loss = GcnLossAndGradient<float>(
            model.params, graph, positive_weight, nullptr, &logits);
        AddPredictions(logits, graph.labels, threshold, &per_sample[s]);
      });
  GcnClassificationStats total;
  for (const auto& stats : per_sample) total.Accumulate(stats);
  if (total.num_nodes > 0) total.loss /= static_cast<double>(total.num_nodes);
  return total;
}

}  // namespace colmap_gcn

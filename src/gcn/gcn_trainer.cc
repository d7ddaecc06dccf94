#include "gcn/gcn_trainer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <random>
#include <sstream>
#include <unordered_set>

#include "gcn/gcn_inference.h"
#include "gcn/gcn_network.h"
#include "util/error.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/threading.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

struct PreparedScene {
  const GcnTrainingScene* scene = nullptr;
  KnnGraph knn;
  QesOptions qes;
  std::unordered_set<uint64_t> positives;

  bool IsPositive(int i, int j) const {
    const uint64_t a = static_cast<uint64_t>(std::min(i, j));
    const uint64_t b = static_cast<uint64_t>(std::max(i, j));
    return positives.count((a << 32) | b) > 0;
  }
};

struct Sample {
  int scene;
  int query;
};

PreparedScene PrepareScene(const GcnTrainingScene& scene,
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
  PreparedScene prepared;
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
    const uint64_t a = static_cast<uint64_t>(std::min(i, j));
    const uint64_t b = static_cast<uint64_t>(std::max(i, j));
    prepared.positives.insert((a << 32) | b);
  }
  return prepared;
}

// Per-thread QES builders, one per scene, created lazily.
class BuilderPool {
 public:
  BuilderPool(const std::vector<PreparedScene>& scenes,
              QesStructureFeatures structure,
              int num_threads)
      : scenes_(scenes), structure_(structure), builders_(num_threads) {
    for (auto& per_thread : builders_) per_thread.resize(scenes.size());
  }
  QesBuilder& Get(int thread, int scene) {
    auto& builder = builders_[thread][scene];
    if (!builder) {
      builder = std::make_unique<QesBuilder>(
          scenes_[scene].knn, scenes_[scene].qes, structure_);
    }
    return *builder;
  }

 private:
  const std::vector<PreparedScene>& scenes_;
  const QesStructureFeatures structure_;
  std::vector<std::vector<std::unique_ptr<QesBuilder>>> builders_;
};

GcnGraph<float> MakeSampleGraph(const GcnModel& model,
                                const PreparedScene& scene,
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

void Accumulate(const GcnClassificationStats& in, GcnClassificationStats* out) {
  out->loss += in.loss;
  out->num_nodes += in.num_nodes;
  out->true_positives += in.true_positives;
  out->false_positives += in.false_positives;
  out->false_negatives += in.false_negatives;
  out->average_precision_sum += in.average_precision_sum;
  out->num_ranked_queries += in.num_ranked_queries;
}

// Forward only; loss is the mean over nodes.
GcnClassificationStats EvaluateSamples(const GcnModel& model,
                                       const std::vector<PreparedScene>& scenes,
                                       const std::vector<Sample>& samples,
                                       float positive_weight,
                                       float threshold,
                                       int num_threads,
                                       BuilderPool* pool) {
  std::vector<GcnClassificationStats> per_sample(samples.size());
  ParallelFor(
      0, static_cast<int>(samples.size()), num_threads, [&](int s, int thread) {
        const Sample& sample = samples[s];
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
  for (const auto& stats : per_sample) Accumulate(stats, &total);
  if (total.num_nodes > 0) total.loss /= static_cast<double>(total.num_nodes);
  return total;
}

std::string FormatStats(const GcnClassificationStats& s) {
  char buffer[128];
  std::snprintf(buffer,
                sizeof(buffer),
                "loss %.4f P %.3f R %.3f F %.3f AP %.3f",
                s.loss,
                s.Precision(),
                s.Recall(),
                s.F(),
                s.MeanAveragePrecision());
  return buffer;
}

}  // namespace

const EnumNames<GcnInitialization>& GcnInitializationNames() {
  static const EnumNames<GcnInitialization> names = {
      {"xavier", GcnInitialization::kXavier},
      {"distance_prior", GcnInitialization::kDistancePrior}};
  return names;
}

const EnumNames<GcnOptimizer>& GcnOptimizerNames() {
  static const EnumNames<GcnOptimizer> names = {{"sgd", GcnOptimizer::kSgd},
                                                {"adam", GcnOptimizer::kAdam}};
  return names;
}

void GcnTrainingOptions::Check() const {
  shape.Check();
  qes.Check();
  test_qes.Check();
  CHECK_OPTION_GE(prior_other_scale, 0.f);
  if (initialization == GcnInitialization::kDistancePrior &&
      !QesUsesEmbeddingDifferences(structure_features)) {
    internal::ThrowOptionError(
        &structure_features,
        "structure_features",
        "keep the embedding differences with the distance prior",
        QesStructureFeaturesName(structure_features));
  }
  CHECK_OPTION_GT(learning_rate, 0.0);
  CHECK_OPTION_GE(momentum, 0.0);
  CHECK_OPTION_GE(weight_decay, 0.0);
  CHECK_OPTION_GE(batch_size, 1);
  CHECK_OPTION_GE(num_epochs, 1);
  CHECK_OPTION_GT(lr_decay_factor, 0.0);
  CHECK_OPTION_INTERVAL(validation_fraction, 0.0, true, 1.0, false);
  CHECK_OPTION_GE(early_stopping_patience, 0);
  CHECK_OPTION_GE(standardization_samples, 1);
  CHECK_OPTION_INTERVAL(threshold, 0.f, false, 1.f, false);
  CHECK_OPTION_NUM_THREADS(num_threads);
}

PrecisionRecall GcnClassificationStats::Scores() const {
  return ComputePrecisionRecall(true_positives,
                                true_positives + false_positives,
                                true_positives + false_negatives);
}

double GcnClassificationStats::Precision() const { return Scores().precision; }

double GcnClassificationStats::Recall() const { return Scores().recall; }

double GcnClassificationStats::F() const { return Scores().f_measure; }

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

double GcnClassificationStats::MeanAveragePrecision() const {
  return num_ranked_queries > 0 ? average_precision_sum / num_ranked_queries
                                : 0.0;
}

GcnTrainer::GcnTrainer(const GcnTrainingOptions& options) : options_(options) {}

GcnModel GcnTrainer::Train(
    const std::vector<GcnTrainingScene>& scenes,
    const std::vector<GcnTrainingScene>& validation_scenes) {
  const GcnTrainingOptions& o = options_;
  o.Check();
  if (scenes.empty()) ThrowError("no training scenes");
  // One line per epoch and a few set-up lines.
  const auto log = [](const std::string& line) { LOG(INFO) << line; };
  const int threads = EffectiveNumThreads(o.num_threads);
  const int dim = static_cast<int>(scenes[0].embeddings.cols());
  for (const auto* list : {&scenes, &validation_scenes}) {
    for (const auto& scene : *list) {
      if (scene.embeddings.cols() != dim) {
        ThrowError("training scene '",
                   scene.name,
                   "' has ",
                   scene.embeddings.cols(),
                   "-dimensional embeddings, expected ",
                   dim);
      }
    }
  }
  history_.clear();
  Timer total_timer;

  // Scenes, kNN graphs and samples.
  std::vector<PreparedScene> prepared;
  for (const auto& scene : scenes) {
    prepared.push_back(PrepareScene(scene, o.qes, threads));
  }
  for (const auto& scene : validation_scenes) {
    prepared.push_back(PrepareScene(scene, o.qes, threads));
  }
  std::vector<Sample> train_samples;
  std::vector<Sample> val_samples;
  std::mt19937 rng(o.seed);
  for (size_t s = 0; s < prepared.size(); ++s) {
    const int n = static_cast<int>(prepared[s].scene->embeddings.rows());
    for (int q = 0; q < n; ++q) {
      (s < scenes.size() ? train_samples : val_samples)
          .push_back({static_cast<int>(s), q});
    }
  }
  if (validation_scenes.empty() && o.validation_fraction > 0) {
    std::shuffle(train_samples.begin(), train_samples.end(), rng);
    const size_t num_val = static_cast<size_t>(
        std::round(o.validation_fraction * train_samples.size()));
    val_samples.assign(train_samples.end() - num_val, train_samples.end());
    train_samples.resize(train_samples.size() - num_val);
    auto by_index = [](const Sample& a, const Sample& b) {
      return a.scene != b.scene ? a.scene < b.scene : a.query < b.query;
    };
    std::sort(train_samples.begin(), train_samples.end(), by_index);
    std::sort(val_samples.begin(), val_samples.end(), by_index);
  }
  if (train_samples.empty()) ThrowError("no training samples");

  GcnShape shape = o.shape;
  const int differences =
      QesUsesEmbeddingDifferences(o.structure_features) ? dim : 0;
  const int input_dim = differences + QesStructureDim(o.structure_features);
  shape.input_dim = input_dim;
  GcnModel model = InitializeGcnModel(shape, o.aggregation, o.seed);
  model.feature_scaling = o.feature_scaling;
  model.structure_features = o.structure_features;
  model.embedding.dim = dim;
  const bool prior = o.initialization == GcnInitialization::kDistancePrior;
  BuilderPool pool(prepared, o.structure_features, threads);

  // Input standardisation from a sample of training subgraphs (the fixed
  // counterpart of gcn_clustering's BatchNorm1d without affine).
  {
    std::vector<Sample> sampled = train_samples;
    std::mt19937 srng(o.seed + 1);
    std::shuffle(sampled.begin(), sampled.end(), srng);
    sampled.resize(std::min<size_t>(sampled.size(), o.standardization_samples));
    std::vector<Eigen::VectorXd> sums(sampled.size()), squares(sampled.size());
    std::vector<int64_t> counts(sampled.size(), 0);
    ParallelFor(
        0, static_cast<int>(sampled.size()), threads, [&](int s, int t) {
          QuerySubgraph subgraph;
          pool.Get(t, sampled[s].scene).Build(sampled[s].query, &subgraph);
          const Eigen::MatrixXd xd =
              QesNodeFeatures(subgraph,
                              prepared[sampled[s].scene].scene->embeddings,
                              o.feature_scaling,
                              o.structure_features)
                  .cast<double>();
          sums[s] = xd.colwise().sum().transpose();
          squares[s] = xd.array().square().colwise().sum().transpose();
          counts[s] = xd.rows();
        });
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(input_dim);
    Eigen::VectorXd square = Eigen::VectorXd::Zero(input_dim);
    int64_t count = 0;
    for (size_t s = 0; s < sampled.size(); ++s) {
      if (counts[s] == 0) continue;
      sum += sums[s];
      square += squares[s];
      count += counts[s];
    }
    auto standardize = [&](int j) {
      const double mean = sum(j) / count;
      const double sd =
          std::sqrt(std::max(0.0, square(j) / count - mean * mean));
      model.input_shift(j) = static_cast<float>(mean);
      model.input_scale(j) = sd > 1e-8 ? static_cast<float>(1.0 / sd) : 1.f;
    };
    if (count > 0 && prior) {
      // One scale for all embedding dimensions and no shift: the prior's
      // d(v) is then the L1 distance between the embeddings (up to the
      // scale). Structural features are standardised one by one.
      const double rms = std::sqrt(square.head(differences).sum() /
                                   (static_cast<double>(count) * differences));
      model.input_scale.head(differences)
          .setConstant(rms > 1e-12 ? static_cast<float>(1.0 / rms) : 1.f);
      for (int j = differences; j < input_dim; ++j) standardize(j);
    } else if (count > 0) {
      for (int j = 0; j < input_dim; ++j) standardize(j);
    }
    if (prior) {
      InitializeDistancePrior(&model, o.prior_other_scale);
      // Calibrate: logits of the sampled subgraphs' 1-hop nodes to median 0
      // and unit standard deviation.
      std::vector<std::vector<float>> per_sample(sampled.size());
      ParallelFor(
          0, static_cast<int>(sampled.size()), threads, [&](int s, int t) {
            const GcnGraph<float> graph =
                MakeSampleGraph(model,
                                prepared[sampled[s].scene],
                                sampled[s].query,
                                &pool.Get(t, sampled[s].scene));
            const ColVector<float> z = GcnForwardReference(model.params, graph);
            per_sample[s].assign(z.data(), z.data() + z.size());
          });
      std::vector<float> logits;
      for (const auto& z : per_sample) {
        logits.insert(logits.end(), z.begin(), z.end());
      }
      if (!logits.empty()) {
        double mean = 0, square_sum = 0;
        for (const float z : logits) mean += z;
        mean /= logits.size();
        for (const float z : logits) square_sum += (z - mean) * (z - mean);
        const double sd = std::sqrt(square_sum / logits.size());
        std::nth_element(
            logits.begin(), logits.begin() + logits.size() / 2, logits.end());
        const double median = logits[logits.size() / 2];
        const float scale = sd > 1e-12 ? static_cast<float>(1.0 / sd) : 1.f;
        model.params.Fc2Weight() *= scale;
        model.params.Fc2Bias() = static_cast<float>(-median * scale);
      }
    }
  }

  // Class balance over the training 1-hop nodes.
  int64_t num_pos = 0;
  int64_t num_one_hop = 0;
  for (const Sample& sample : train_samples) {
    const PreparedScene& scene = prepared[sample.scene];
    for (int i = 0; i < scene.qes.k1; ++i) {
      num_pos +=
          scene.IsPositive(sample.query, scene.knn.indices(sample.query, i));
    }
    num_one_hop += scene.qes.k1;
  }
  float positive_weight = static_cast<float>(o.positive_weight);
  if (o.positive_weight <= 0) {
    positive_weight = num_pos > 0
                          ? std::min(100.f,
                                     static_cast<float>(num_one_hop - num_pos) /
                                         std::max<int64_t>(num_pos, 1))
                          : 1.f;
  }
  {
    std::ostringstream line;
    line << "GCN training: " << scenes.size() << " scene(s), "
         << train_samples.size() << " training / " << val_samples.size()
         << " validation subgraphs, 1-hop positives " << num_pos << " / "
         << num_one_hop << ", positive weight " << positive_weight
         << ", optimizer " << EnumName(GcnOptimizerNames(), o.optimizer) << ", "
         << threads << " thread(s)";
    log(line.str());
  }

  // Optimiser state.
  std::vector<float>& params = model.params.Values();
  std::vector<float> state1(params.size());  // zeros
  std::vector<float> state2(params.size());
  int64_t step = 0;
  std::vector<GcnParameters<float>> sample_grads(
      std::min<size_t>(o.batch_size, train_samples.size()),
      GcnParameters<float>(shape));
  std::vector<double> grad(params.size());

  GcnModel best_model = model;
  double best_ap = -1;
  int best_epoch = -1;
  int epochs_without_improvement = 0;
  auto validate = [&]() {
    return EvaluateSamples(model,
                           prepared,
                           val_samples,
                           positive_weight,
                           o.threshold,
                           threads,
                           &pool);
  };
  if (prior && !val_samples.empty()) {
    // The starting point is a candidate model too.
    const GcnClassificationStats initial = validate();
    best_ap = initial.MeanAveragePrecision();
    best_epoch = 0;
    log("epoch 0 (distance prior) | val " + FormatStats(initial));
  }
  double lr = o.learning_rate;
  for (int epoch = 0; epoch < o.num_epochs; ++epoch) {
    Timer timer;
    if (std::find(o.lr_decay_epochs.begin(), o.lr_decay_epochs.end(), epoch) !=
        o.lr_decay_epochs.end()) {
      lr *= o.lr_decay_factor;
    }
    std::vector<Sample> order = train_samples;
    std::mt19937 erng(o.seed * 7919u + 104729u * (epoch + 1));
    std::shuffle(order.begin(), order.end(), erng);
    if (o.max_samples_per_epoch > 0 &&
        static_cast<int>(order.size()) > o.max_samples_per_epoch) {
      order.resize(o.max_samples_per_epoch);
    }

    GcnEpochStats stats;
    stats.epoch = epoch + 1;
    stats.learning_rate = lr;
    std::vector<GcnClassificationStats> batch_stats(sample_grads.size());
    for (size_t begin = 0; begin < order.size(); begin += o.batch_size) {
      const int count = static_cast<int>(
          std::min<size_t>(o.batch_size, order.size() - begin));
      ParallelFor(0, count, threads, [&](int i, int t) {
        const Sample& sample = order[begin + i];
        const GcnGraph<float> graph =
            MakeSampleGraph(model,
                            prepared[sample.scene],
                            sample.query,
                            &pool.Get(t, sample.scene));
        sample_grads[i].SetZero();
        ColVector<float> logits;
        batch_stats[i] = GcnClassificationStats();
        batch_stats[i].loss = GcnLossAndGradient<float>(
            model.params, graph, positive_weight, &sample_grads[i], &logits);
        AddPredictions(logits, graph.labels, o.threshold, &batch_stats[i]);
      });
      int64_t nodes = 0;
      for (int i = 0; i < count; ++i) {
        nodes += batch_stats[i].num_nodes;
        Accumulate(batch_stats[i], &stats.train);
      }
      if (nodes == 0) continue;
      // Sum the per-sample gradients in sample order (thread independent).
      std::fill(grad.begin(), grad.end(), 0.0);
      for (int i = 0; i < count; ++i) {
        const std::vector<float>& g = sample_grads[i].Values();
        for (size_t j = 0; j < grad.size(); ++j) grad[j] += g[j];
      }
      ++step;
      const double inv_nodes = 1.0 / static_cast<double>(nodes);
      if (o.optimizer == GcnOptimizer::kSgd) {
        for (size_t j = 0; j < params.size(); ++j) {
          const double d = grad[j] * inv_nodes + o.weight_decay * params[j];
          const double v = step == 1 ? d : o.momentum * state1[j] + d;
          state1[j] = static_cast<float>(v);
          params[j] = static_cast<float>(params[j] - lr * v);
        }
      } else {
        const double c1 =
            1.0 - std::pow(o.adam_beta1, static_cast<double>(step));
        const double c2 =
            1.0 - std::pow(o.adam_beta2, static_cast<double>(step));
        for (size_t j = 0; j < params.size(); ++j) {
          const double d = grad[j] * inv_nodes + o.weight_decay * params[j];
          const double m = o.adam_beta1 * state1[j] + (1 - o.adam_beta1) * d;
          const double v =
              o.adam_beta2 * state2[j] + (1 - o.adam_beta2) * d * d;
          state1[j] = static_cast<float>(m);
          state2[j] = static_cast<float>(v);
          params[j] = static_cast<float>(
              params[j] - lr * (m / c1) / (std::sqrt(v / c2) + o.adam_epsilon));
        }
      }
    }
    if (stats.train.num_nodes > 0) stats.train.loss /= stats.train.num_nodes;

    bool improved = true;
    if (!val_samples.empty()) {
      stats.validation = validate();
      improved = stats.validation.MeanAveragePrecision() > best_ap + 1e-12;
    }
    stats.seconds = timer.ElapsedSeconds();
    history_.push_back(stats);
    {
      std::ostringstream line;
      line << "epoch " << stats.epoch << "/" << o.num_epochs << " lr " << lr
           << " | train " << FormatStats(stats.train);
      if (!val_samples.empty())
        line << " | val " << FormatStats(stats.validation);
      char seconds[32];
      std::snprintf(seconds, sizeof(seconds), " | %.1f s", stats.seconds);
      line << seconds;
      log(line.str());
    }
    if (improved) {
      best_ap =
          val_samples.empty() ? -1 : stats.validation.MeanAveragePrecision();
      best_model = model;
      best_epoch = epoch + 1;
      epochs_without_improvement = 0;
    } else if (o.early_stopping_patience > 0 &&
               ++epochs_without_improvement >= o.early_stopping_patience) {
      log("early stopping: no better validation AP for " +
          std::to_string(o.early_stopping_patience) + " epoch(s)");
      break;
    }
  }

  // Metadata.
  best_model.embedding.dim = dim;
  best_model.info.tau_mo = o.tau_mo;
  best_model.info.tau_ct = o.tau_ct;
  best_model.info.test_k1 = o.test_qes.k1;
  best_model.info.test_k2 = o.test_qes.k2;
  best_model.info.test_u = o.test_qes.u;
  best_model.info.threshold = o.threshold;
  {
    int64_t images = 0;
    int64_t pairs = 0;
    for (const auto& p : prepared) {
      images += p.scene->embeddings.rows();
      pairs += static_cast<int64_t>(p.positives.size());
    }
    std::ostringstream notes;
    notes << "trained on " << scenes.size() << " scene(s) + "
          << validation_scenes.size() << " validation scene(s), " << images
          << " images, " << pairs << " positive pairs; QES k1=" << o.qes.k1
          << " k2=" << o.qes.k2 << " u=" << o.qes.u << "; "
          << GcnAggregationName(o.aggregation) << " aggregation; "
          << EnumName(GcnOptimizerNames(), o.optimizer) << " lr "
          << o.learning_rate << ", batch " << o.batch_size
          << ", positive weight " << positive_weight << ", seed " << o.seed
          << "; " << EnumName(GcnInitializationNames(), o.initialization)
          << " initialisation; " << train_samples.size() << " train / "
          << val_samples.size() << " val subgraphs; best epoch " << best_epoch
          << " of " << history_.size();
    if (o.feature_scaling != QesFeatureScaling::kNone) {
      notes << "; " << QesFeatureScalingName(o.feature_scaling)
            << " feature scaling";
    }
    if (o.structure_features != QesStructureFeatures::kNone) {
      notes << "; " << QesStructureFeaturesName(o.structure_features)
            << " structural features";
    }
    if (best_epoch > 0 && !val_samples.empty()) {
      notes << " (val " << FormatStats(history_[best_epoch - 1].validation)
            << ")";
    }
    best_model.info.notes = notes.str();
  }
  char seconds[64];
  std::snprintf(
      seconds, sizeof(seconds), "%.1f s", total_timer.ElapsedSeconds());
  log(std::string("GCN training done in ") + seconds + ", best epoch " +
      std::to_string(best_epoch));
  return best_model;
}

GcnClassificationStats EvaluateGcn(const GcnModel& model,
                                   const std::vector<GcnTrainingScene>& scenes,
                                   const QesOptions& qes,
                                   float threshold,
                                   int num_threads) {
  const int threads = EffectiveNumThreads(num_threads);
  std::vector<PreparedScene> prepared;
  std::vector<Sample> samples;
  for (size_t s = 0; s < scenes.size(); ++s) {
    model.CheckEmbeddingDimension(
        static_cast<int>(scenes[s].embeddings.cols()));
    prepared.push_back(PrepareScene(scenes[s], qes, threads));
    for (int q = 0; q < scenes[s].embeddings.rows(); ++q) {
      samples.push_back({static_cast<int>(s), q});
    }
  }
  BuilderPool pool(prepared, model.structure_features, threads);
  return EvaluateSamples(
      model, prepared, samples, 1.f, threshold, threads, &pool);
}

}  // namespace colmap_gcn

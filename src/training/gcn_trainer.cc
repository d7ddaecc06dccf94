#include "training/gcn_trainer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>

#include "training/distance_prior.h"
#include "training/gcn_network.h"
#include "training/gcn_optimizer.h"
#include "util/error.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/threading.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

// The prepared scenes (training scenes first, then validation scenes) and
// the samples of each role.
struct TrainingSet {
  std::vector<PreparedTrainingScene> scenes;
  size_t num_training_scenes = 0;
  std::vector<TrainingSample> train;
  std::vector<TrainingSample> validation;
};

// The embedding dimension all scenes share; throws Error naming a scene
// that differs.
int CheckEmbeddingDimensions(
    const std::vector<GcnTrainingScene>& scenes,
    const std::vector<GcnTrainingScene>& validation_scenes) {
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
  return dim;
}

// kNN graphs of every scene and one sample per (scene, query). Without
// validation scenes, a random validation_fraction of the training samples
// validates; both lists stay in (scene, query) order.
TrainingSet PrepareTrainingSet(
    const std::vector<GcnTrainingScene>& scenes,
    const std::vector<GcnTrainingScene>& validation_scenes,
    const GcnTrainingOptions& options,
    int num_threads) {
  TrainingSet set;
  set.num_training_scenes = scenes.size();
  for (const auto& scene : scenes) {
    set.scenes.push_back(PrepareTrainingScene(scene, options.qes, num_threads));
  }
  for (const auto& scene : validation_scenes) {
    set.scenes.push_back(PrepareTrainingScene(scene, options.qes, num_threads));
  }
  for (size_t s = 0; s < set.scenes.size(); ++s) {
    const int n = static_cast<int>(set.scenes[s].scene->embeddings.rows());
    for (int q = 0; q < n; ++q) {
      (s < scenes.size() ? set.train : set.validation)
          .push_back({static_cast<int>(s), q});
    }
  }
  if (validation_scenes.empty() && options.validation_fraction > 0) {
    std::mt19937 rng(options.seed);
    std::shuffle(set.train.begin(), set.train.end(), rng);
    const size_t num_val = static_cast<size_t>(
        std::round(options.validation_fraction * set.train.size()));
    set.validation.assign(set.train.end() - num_val, set.train.end());
    set.train.resize(set.train.size() - num_val);
    auto by_index = [](const TrainingSample& a, const TrainingSample& b) {
      return a.scene != b.scene ? a.scene < b.scene : a.query < b.query;
    };
    std::sort(set.train.begin(), set.train.end(), by_index);
    std::sort(set.validation.begin(), set.validation.end(), by_index);
  }
  if (set.train.empty()) ThrowError("no training samples");
  return set;
}

// Number of network inputs that are embedding differences.
int DifferenceDim(const GcnTrainingOptions& options, int embedding_dim) {
  return QesUsesEmbeddingDifferences(options.structure_features) ? embedding_dim
                                                                 : 0;
}

// Xavier weights for the network that reads embeddings of `embedding_dim`.
GcnModel InitialModel(const GcnTrainingOptions& options, int embedding_dim) {
  GcnShape shape = options.shape;
  shape.input_dim = DifferenceDim(options, embedding_dim) +
                    QesStructureDim(options.structure_features);
  GcnModel model = InitializeGcnModel(shape, options.aggregation, options.seed);
  model.feature_scaling = options.feature_scaling;
  model.structure_features = options.structure_features;
  model.embedding.dim = embedding_dim;
  return model;
}

// The training subgraphs the input standardisation is estimated on.
std::vector<TrainingSample> StandardizationSamples(
    const TrainingSet& set, const GcnTrainingOptions& options) {
  std::vector<TrainingSample> sampled = set.train;
  std::mt19937 rng(options.seed + 1);
  std::shuffle(sampled.begin(), sampled.end(), rng);
  sampled.resize(
      std::min<size_t>(sampled.size(), options.standardization_samples));
  return sampled;
}

// Input standardisation from the sampled training subgraphs (the fixed
// counterpart of gcn_clustering's BatchNorm1d without affine).
void EstimateStandardization(const GcnTrainingOptions& options,
                             const TrainingSet& set,
                             const std::vector<TrainingSample>& sampled,
                             int num_threads,
                             QesBuilderPool* pool,
                             GcnModel* model) {
  const int input_dim = model->shape.input_dim;
  const int differences = DifferenceDim(options, model->embedding.dim);
  std::vector<Eigen::VectorXd> sums(sampled.size()), squares(sampled.size());
  std::vector<int64_t> counts(sampled.size(), 0);
  ParallelFor(
      0, static_cast<int>(sampled.size()), num_threads, [&](int s, int t) {
        QuerySubgraph subgraph;
        pool->Get(t, sampled[s].scene).Build(sampled[s].query, &subgraph);
        const Eigen::MatrixXd xd =
            QesNodeFeatures(subgraph,
                            set.scenes[sampled[s].scene].scene->embeddings,
                            options.feature_scaling,
                            options.structure_features)
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
  if (count == 0) return;
  auto standardize = [&](int j) {
    const double mean = sum(j) / count;
    const double sd = std::sqrt(std::max(0.0, square(j) / count - mean * mean));
    model->input_shift(j) = static_cast<float>(mean);
    model->input_scale(j) = sd > 1e-8 ? static_cast<float>(1.0 / sd) : 1.f;
  };
  if (options.initialization == GcnInitialization::kDistancePrior) {
    // One scale for all embedding dimensions and no shift: the prior's
    // d(v) is then the L1 distance between the embeddings (up to the
    // scale). Structural features are standardised one by one.
    const double rms = std::sqrt(square.head(differences).sum() /
                                 (static_cast<double>(count) * differences));
    model->input_scale.head(differences)
        .setConstant(rms > 1e-12 ? static_cast<float>(1.0 / rms) : 1.f);
    for (int j = differences; j < input_dim; ++j) standardize(j);
  } else {
    for (int j = 0; j < input_dim; ++j) standardize(j);
  }
}

// The distance prior, its output calibrated on the sampled subgraphs: the
// logits of their 1-hop nodes to median 0 and unit standard deviation.
void StartFromDistancePrior(const GcnTrainingOptions& options,
                            const TrainingSet& set,
                            const std::vector<TrainingSample>& sampled,
                            int num_threads,
                            QesBuilderPool* pool,
                            GcnModel* model) {
  InitializeDistancePrior(model, options.prior_other_scale);
  std::vector<std::vector<float>> per_sample(sampled.size());
  ParallelFor(
      0, static_cast<int>(sampled.size()), num_threads, [&](int s, int t) {
        const GcnGraph<float> graph =
            MakeSampleGraph(*model,
                            set.scenes[sampled[s].scene],
                            sampled[s].query,
                            &pool->Get(t, sampled[s].scene));
        const ColVector<float> z = GcnForwardReference(model->params, graph);
        per_sample[s].assign(z.data(), z.data() + z.size());
      });
  std::vector<float> logits;
  for (const auto& z : per_sample) {
    logits.insert(logits.end(), z.begin(), z.end());
  }
  if (logits.empty()) return;
  double mean = 0, square_sum = 0;
  for (const float z : logits) mean += z;
  mean /= logits.size();
  for (const float z : logits) square_sum += (z - mean) * (z - mean);
  const double sd = std::sqrt(square_sum / logits.size());
  std::nth_element(
      logits.begin(), logits.begin() + logits.size() / 2, logits.end());
  const double median = logits[logits.size() / 2];
  const float scale = sd > 1e-12 ? static_cast<float>(1.0 / sd) : 1.f;
  model->params.Fc2Weight() *= scale;
  model->params.Fc2Bias() = static_cast<float>(-median * scale);
}

// Positives among the training 1-hop nodes and the BCE's positive weight.
struct ClassBalance {
  int64_t num_positive = 0;
  int64_t num_one_hop = 0;
  float positive_weight = 1.f;
};

ClassBalance ComputeClassBalance(const GcnTrainingOptions& options,
                                 const TrainingSet& set) {
  ClassBalance balance;
  for (const TrainingSample& sample : set.train) {
    const PreparedTrainingScene& scene = set.scenes[sample.scene];
    for (int i = 0; i < scene.qes.k1; ++i) {
      balance.num_positive +=
          scene.IsPositive(sample.query, scene.knn.indices(sample.query, i));
    }
    balance.num_one_hop += scene.qes.k1;
  }
  balance.positive_weight = static_cast<float>(options.positive_weight);
  if (options.positive_weight <= 0) {
    balance.positive_weight =
        balance.num_positive > 0
            ? std::min(100.f,
                       static_cast<float>(balance.num_one_hop -
                                          balance.num_positive) /
                           std::max<int64_t>(balance.num_positive, 1))
            : 1.f;
  }
  return balance;
}

// Gradient steps over batches of training samples: the per-sample
// gradients run in parallel and are summed in sample order, so the result
// does not depend on the thread count.
class BatchTrainer {
 public:
  BatchTrainer(const GcnTrainingOptions& options,
               const TrainingSet& set,
               float positive_weight,
               int num_threads,
               QesBuilderPool* pool,
               GcnModel* model)
      : options_(options),
        set_(set),
        positive_weight_(positive_weight),
        num_threads_(num_threads),
        pool_(pool),
        model_(model),
        optimizer_(options, model->params.Size()),
        sample_grads_(std::min<size_t>(options.batch_size, set.train.size()),
                      GcnParameters<float>(model->params.Shape())),
        batch_stats_(sample_grads_.size()),
        grad_(model->params.Size()) {}

  // One pass over `order` in batches; the loss is the mean over nodes.
  GcnClassificationStats RunEpoch(const std::vector<TrainingSample>& order,
                                  double learning_rate) {
    GcnClassificationStats stats;
    for (size_t begin = 0; begin < order.size(); begin += options_.batch_size) {
      const int count = static_cast<int>(
          std::min<size_t>(options_.batch_size, order.size() - begin));
      RunBatch(order, begin, count, learning_rate, &stats);
    }
    if (stats.num_nodes > 0) stats.loss /= stats.num_nodes;
    return stats;
  }

 private:
  void RunBatch(const std::vector<TrainingSample>& order,
                size_t begin,
                int count,
                double learning_rate,
                GcnClassificationStats* stats) {
    ParallelFor(0, count, num_threads_, [&](int i, int t) {
      const TrainingSample& sample = order[begin + i];
      const GcnGraph<float> graph =
          MakeSampleGraph(*model_,
                          set_.scenes[sample.scene],
                          sample.query,
                          &pool_->Get(t, sample.scene));
      sample_grads_[i].SetZero();
      ColVector<float> logits;
      batch_stats_[i] = GcnClassificationStats();
      batch_stats_[i].loss = GcnLossAndGradient<float>(
          model_->params, graph, positive_weight_, &sample_grads_[i], &logits);
      AddPredictions(
          logits, graph.labels, options_.threshold, &batch_stats_[i]);
    });
    int64_t nodes = 0;
    for (int i = 0; i < count; ++i) {
      nodes += batch_stats_[i].num_nodes;
      stats->Accumulate(batch_stats_[i]);
    }
    if (nodes == 0) return;
    std::fill(grad_.begin(), grad_.end(), 0.0);
    for (int i = 0; i < count; ++i) {
      const std::vector<float>& g = sample_grads_[i].Values();
      for (size_t j = 0; j < grad_.size(); ++j) grad_[j] += g[j];
    }
    optimizer_.Step(grad_, nodes, learning_rate, &model_->params.Values());
  }

  const GcnTrainingOptions& options_;
  const TrainingSet& set_;
  const float positive_weight_;
  const int num_threads_;
  QesBuilderPool* pool_;
  GcnModel* model_;
  GcnParameterOptimizer optimizer_;
  std::vector<GcnParameters<float>> sample_grads_;
  std::vector<GcnClassificationStats> batch_stats_;
  std::vector<double> grad_;
};

// The learning rate of a (0-based) epoch after the step decays.
double DecayedLearningRate(const GcnTrainingOptions& options,
                           int epoch,
                           double learning_rate) {
  if (std::find(options.lr_decay_epochs.begin(),
                options.lr_decay_epochs.end(),
                epoch) != options.lr_decay_epochs.end()) {
    learning_rate *= options.lr_decay_factor;
  }
  return learning_rate;
}

// The epoch's training samples: a seeded shuffle, cut to
// max_samples_per_epoch.
std::vector<TrainingSample> EpochSamples(const GcnTrainingOptions& options,
                                         const TrainingSet& set,
                                         int epoch) {
  std::vector<TrainingSample> order = set.train;
  std::mt19937 rng(options.seed * 7919u + 104729u * (epoch + 1));
  std::shuffle(order.begin(), order.end(), rng);
  if (options.max_samples_per_epoch > 0 &&
      static_cast<int>(order.size()) > options.max_samples_per_epoch) {
    order.resize(options.max_samples_per_epoch);
  }
  return order;
}

void LogTrainingStart(const GcnTrainingOptions& options,
                      const TrainingSet& set,
                      const ClassBalance& balance,
                      int num_threads) {
  LOG(INFO) << "GCN training: " << set.num_training_scenes << " scene(s), "
            << set.train.size() << " training / " << set.validation.size()
            << " validation subgraphs, 1-hop positives " << balance.num_positive
            << " / " << balance.num_one_hop << ", positive weight "
            << balance.positive_weight << ", optimizer "
            << EnumName(GcnOptimizerNames(), options.optimizer) << ", "
            << num_threads << " thread(s)";
}

void LogEpoch(const GcnEpochStats& stats,
              int num_epochs,
              bool with_validation) {
  std::ostringstream line;
  line << "epoch " << stats.epoch << "/" << num_epochs << " lr "
       << stats.learning_rate << " | train " << stats.train.Format();
  if (with_validation) line << " | val " << stats.validation.Format();
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), " | %.1f s", stats.seconds);
  line << seconds;
  LOG(INFO) << line.str();
}

// What the model was trained on and how, for its info.notes.
std::string TrainingNotes(const GcnTrainingOptions& o,
                          const TrainingSet& set,
                          size_t num_validation_scenes,
                          float positive_weight,
                          int best_epoch,
                          const std::vector<GcnEpochStats>& history) {
  int64_t images = 0;
  int64_t pairs = 0;
  for (const auto& p : set.scenes) {
    images += p.scene->embeddings.rows();
    pairs += static_cast<int64_t>(p.positives.size());
  }
  std::ostringstream notes;
  notes << "trained on " << set.num_training_scenes << " scene(s) + "
        << num_validation_scenes << " validation scene(s), " << images
        << " images, " << pairs << " positive pairs; QES k1=" << o.qes.k1
        << " k2=" << o.qes.k2 << " u=" << o.qes.u << "; "
        << GcnAggregationName(o.aggregation) << " aggregation; "
        << EnumName(GcnOptimizerNames(), o.optimizer) << " lr "
        << o.learning_rate << ", batch " << o.batch_size << ", positive weight "
        << positive_weight << ", seed " << o.seed << "; "
        << EnumName(GcnInitializationNames(), o.initialization)
        << " initialisation; " << set.train.size() << " train / "
        << set.validation.size() << " val subgraphs; best epoch " << best_epoch
        << " of " << history.size();
  if (o.feature_scaling != QesFeatureScaling::kNone) {
    notes << "; " << QesFeatureScalingName(o.feature_scaling)
          << " feature scaling";
  }
  if (o.structure_features != QesStructureFeatures::kNone) {
    notes << "; " << QesStructureFeaturesName(o.structure_features)
          << " structural features";
  }
  if (best_epoch > 0 && !set.validation.empty()) {
    notes << " (val " << history[best_epoch - 1].validation.Format() << ")";
  }
  return notes.str();
}

// The labels and test settings the model is stored with.
void SetModelInfo(const GcnTrainingOptions& options,
                  int embedding_dim,
                  GcnModel* model) {
  model->embedding.dim = embedding_dim;
  model->info.tau_mo = options.tau_mo;
  model->info.tau_ct = options.tau_ct;
  model->info.test_k1 = options.test_qes.k1;
  model->info.test_k2 = options.test_qes.k2;
  model->info.test_u = options.test_qes.u;
  model->info.threshold = options.threshold;
}

}  // namespace

GcnTrainer::GcnTrainer(const GcnTrainingOptions& options) : options_(options) {}

GcnModel GcnTrainer::Train(
    const std::vector<GcnTrainingScene>& scenes,
    const std::vector<GcnTrainingScene>& validation_scenes) {
  const GcnTrainingOptions& o = options_;
  o.Check();
  if (scenes.empty()) ThrowError("no training scenes");
  const int threads = EffectiveNumThreads(o.num_threads);
  const int dim = CheckEmbeddingDimensions(scenes, validation_scenes);
  history_.clear();
  Timer total_timer;

  const TrainingSet set =
      PrepareTrainingSet(scenes, validation_scenes, o, threads);
  GcnModel model = InitialModel(o, dim);
  const bool prior = o.initialization == GcnInitialization::kDistancePrior;
  QesBuilderPool pool(set.scenes, o.structure_features, threads);
  {
    const std::vector<TrainingSample> sampled = StandardizationSamples(set, o);
    EstimateStandardization(o, set, sampled, threads, &pool, &model);
    if (prior) {
      StartFromDistancePrior(o, set, sampled, threads, &pool, &model);
    }
  }
  const ClassBalance balance = ComputeClassBalance(o, set);
  LogTrainingStart(o, set, balance, threads);

  BatchTrainer trainer(o, set, balance.positive_weight, threads, &pool, &model);
  const bool with_validation = !set.validation.empty();
  auto validate = [&]() {
    return EvaluateSamples(model,
                           set.scenes,
                           set.validation,
                           balance.positive_weight,
                           o.threshold,
                           threads,
                           &pool);
  };
  // Early stopping on the validation mean AP; the best model is returned.
  GcnModel best_model = model;
  double best_ap = -1;
  int best_epoch = -1;
  int epochs_without_improvement = 0;
  if (prior && with_validation) {
    // The starting point is a candidate model too.
    const GcnClassificationStats initial = validate();
    best_ap = initial.MeanAveragePrecision();
    best_epoch = 0;
    LOG(INFO) << "epoch 0 (distance prior) | val " << initial.Format();
  }
  double lr = o.learning_rate;
  // Every epoch has its own line; this adds the rate and ETA at each 10 %.
  ProgressLogger progress(o.num_epochs, "GCN training", "epochs", 1e9);
  for (int epoch = 0; epoch < o.num_epochs; ++epoch) {
    Timer timer;
    lr = DecayedLearningRate(o, epoch, lr);
    GcnEpochStats stats;
    stats.epoch = epoch + 1;
    stats.learning_rate = lr;
    stats.train = trainer.RunEpoch(EpochSamples(o, set, epoch), lr);
    bool improved = true;
    if (with_validation) {
      stats.validation = validate();
      improved = stats.validation.MeanAveragePrecision() > best_ap + 1e-12;
    }
    stats.seconds = timer.ElapsedSeconds();
    history_.push_back(stats);
    LogEpoch(stats, o.num_epochs, with_validation);
    progress.Increment();
    if (improved) {
      best_ap = with_validation ? stats.validation.MeanAveragePrecision() : -1;
      best_model = model;
      best_epoch = epoch + 1;
      epochs_without_improvement = 0;
    } else if (o.early_stopping_patience > 0 &&
               ++epochs_without_improvement >= o.early_stopping_patience) {
      LOG(INFO) << "early stopping: no better validation AP for "
                << o.early_stopping_patience << " epoch(s)";
      break;
    }
  }

  SetModelInfo(o, dim, &best_model);
  best_model.info.notes = TrainingNotes(o,
                                        set,
                                        validation_scenes.size(),
                                        balance.positive_weight,
                                        best_epoch,
                                        history_);
  char seconds[64];
  std::snprintf(
      seconds, sizeof(seconds), "%.1f s", total_timer.ElapsedSeconds());
  LOG(INFO) << "GCN training done in " << seconds << ", best epoch "
            << best_epoch;
  return best_model;
}

GcnClassificationStats EvaluateGcn(const GcnModel& model,
                                   const std::vector<GcnTrainingScene>& scenes,
                                   const QesOptions& qes,
                                   float threshold,
                                   int num_threads) {
  const int threads = EffectiveNumThreads(num_threads);
  std::vector<PreparedTrainingScene> prepared;
  std::vector<TrainingSample> samples;
  for (size_t s = 0; s < scenes.size(); ++s) {
    model.CheckEmbeddingDimension(
        static_cast<int>(scenes[s].embeddings.cols()));
    prepared.push_back(PrepareTrainingScene(scenes[s], qes, threads));
    for (int q = 0; q < scenes[s].embeddings.rows(); ++q) {
      samples.push_back({static_cast<int>(s), q});
    }
  }
  QesBuilderPool pool(prepared, model.structure_features, threads);
  return EvaluateSamples(
      model, prepared, samples, 1.f, threshold, threads, &pool);
}

}  // namespace colmap_gcn

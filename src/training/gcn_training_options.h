#pragma once

#include <cstdint>
#include <vector>

#include "gcn/gcn_model.h"
#include "gcn/query_enclosing_subgraph.h"
#include "util/option_check.h"

namespace colmap_gcn {

// How training starts (GcnTrainingOptions::initialization).
enum class GcnInitialization { kXavier, kDistancePrior };
// "xavier", "distance_prior".
const EnumNames<GcnInitialization>& GcnInitializationNames();

// The optimiser (GcnTrainingOptions::optimizer).
enum class GcnOptimizer { kSgd, kAdam };
// "sgd", "adam".
const EnumNames<GcnOptimizer>& GcnOptimizerNames();

struct GcnTrainingOptions {
  // Network; shape.input_dim is taken from the embeddings.
  GcnShape shape;
  GcnAggregation aggregation = GcnAggregation::kSymmetric;
  // Per-query scaling of the node features (stored in the model).
  QesFeatureScaling feature_scaling = QesFeatureScaling::kNone;
  // Structural node features after, or (reciprocal_only) instead of, the
  // embedding differences (stored in the model).
  QesStructureFeatures structure_features = QesStructureFeatures::kNone;

  // kXavier (gcn_clustering's random start) or kDistancePrior: start
  // from the context-aware distance classifier (InitializeDistancePrior)
  // with one global input scale instead of per-dimension standardisation,
  // its output calibrated to median 0 / unit spread on the training
  // subgraphs, and the starting point evaluated as "epoch 0" (kept when no
  // epoch beats it on validation).
  GcnInitialization initialization = GcnInitialization::kXavier;
  // Scale of the Xavier weights of the units the prior does not use.
  float prior_other_scale = 0.1f;

  // QES used for the training samples (paper: k1 = 100, k2 = 5, u = 10).
  QesOptions qes{100, 5, 10};

  // kSgd (momentum, torch semantics) or kAdam.
  GcnOptimizer optimizer = GcnOptimizer::kSgd;
  double learning_rate = 0.01;
  double momentum = 0.9;
  double weight_decay = 1e-4;
  double adam_beta1 = 0.9;
  double adam_beta2 = 0.999;
  double adam_epsilon = 1e-8;
  // Subgraphs per optimiser step (gradients averaged over their 1-hop nodes).
  int batch_size = 16;
  int num_epochs = 4;
  // Step decay: the learning rate is multiplied by lr_decay_factor at the
  // start of each listed (0-based) epoch.
  std::vector<int> lr_decay_epochs = {2, 3};
  double lr_decay_factor = 0.1;

  // Weight of positive nodes in the BCE; <= 0 = balanced (#neg / #pos over
  // the training 1-hop nodes, at most 100).
  double positive_weight = 1.0;

  // Fraction of the (scene, query) samples held out for validation when no
  // validation scenes are given.
  double validation_fraction = 0.1;
  // Stop after this many epochs without a better validation mean average
  // precision (0 = never); the best model by it is returned. Ranking, not F
  // at a fixed threshold: the decision threshold is chosen afterwards.
  int early_stopping_patience = 2;
  // Random subset of the training samples per epoch (-1 = all).
  int max_samples_per_epoch = -1;
  // Training subgraphs sampled to estimate the input standardisation.
  int standardization_samples = 256;

  // Decision threshold for precision / recall and stored in the model.
  float threshold = 0.5f;
  // Stored in the model (training labels and recommended test settings).
  float tau_mo = 0.25f;
  float tau_ct = 0.15f;
  QesOptions test_qes{100, 5, 5};

  uint32_t seed = 0;
  // Threads; -1 = all cores. The result does not depend on it.
  int num_threads = -1;
  // Throws OptionError naming the first invalid field.
  void Check() const;
};

}  // namespace colmap_gcn

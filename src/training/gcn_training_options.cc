#include "training/gcn_training_options.h"

namespace colmap_gcn {

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

}  // namespace colmap_gcn

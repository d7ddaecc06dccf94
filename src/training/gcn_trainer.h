#pragma once

#include <cstdint>
#include <vector>

#include "gcn/gcn_model.h"
#include "gcn/query_enclosing_subgraph.h"
#include "training/gcn_training_options.h"
#include "training/gcn_training_samples.h"

namespace colmap_gcn {

struct GcnEpochStats {
  int epoch = 0;
  double learning_rate = 0;
  GcnClassificationStats train;
  GcnClassificationStats validation;
  double seconds = 0;
};

class GcnTrainer {
 public:
  explicit GcnTrainer(const GcnTrainingOptions& options);

  // Trains on the scenes; validates on validation_scenes, or on a random
  // validation_fraction of the (scene, query) samples when empty.
  // Deterministic for a given seed, whatever num_threads.
  GcnModel Train(const std::vector<GcnTrainingScene>& scenes,
                 const std::vector<GcnTrainingScene>& validation_scenes = {});

  const std::vector<GcnEpochStats>& History() const { return history_; }

 private:
  GcnTrainingOptions options_;
  std::vector<GcnEpochStats> history_;
};

// Classification statistics of a model on the 1-hop nodes of every query of
// the scenes (QES from `qes`), e.g. for held-out evaluation.
GcnClassificationStats EvaluateGcn(const GcnModel& model,
                                   const std::vector<GcnTrainingScene>& scenes,
                                   const QesOptions& qes,
                                   float threshold,
                                   int num_threads);

}  // namespace colmap_gcn

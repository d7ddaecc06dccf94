#pragma once

#include <cstdint>
#include <vector>

#include "training/gcn_training_options.h"

namespace colmap_gcn {

// SGD with momentum (torch semantics) or Adam (options.optimizer) on the
// network's flat parameter array, with weight decay.
class GcnParameterOptimizer {
 public:
  // `options` must outlive the optimiser.
  GcnParameterOptimizer(const GcnTrainingOptions& options, size_t num_params);

  // One step with `grad`, the gradient summed over `num_nodes` nodes (> 0).
  void Step(const std::vector<double>& grad,
            int64_t num_nodes,
            double learning_rate,
            std::vector<float>* params);

 private:
  const GcnTrainingOptions& options_;
  std::vector<float> state1_;  // momentum, or Adam's first moment
  std::vector<float> state2_;  // Adam's second moment
  int64_t step_ = 0;
};

}  // namespace colmap_gcn

#include "training/gcn_optimizer.h"

#include <cmath>

namespace colmap_gcn {

GcnParameterOptimizer::GcnParameterOptimizer(const GcnTrainingOptions& options,
                                             size_t num_params)
    : options_(options), state1_(num_params), state2_(num_params) {}

void GcnParameterOptimizer::Step(const std::vector<double>& grad,
                                 int64_t num_nodes,
                                 double learning_rate,
                                 std::vector<float>* params) {
  const GcnTrainingOptions& o = options_;
  std::vector<float>& p = *params;
  ++step_;
  const double inv_nodes = 1.0 / static_cast<double>(num_nodes);
  if (o.optimizer == GcnOptimizer::kSgd) {
    for (size_t j = 0; j < p.size(); ++j) {
      const double d = grad[j] * inv_nodes + o.weight_decay * p[j];
      const double v = step_ == 1 ? d : o.momentum * state1_[j] + d;
      state1_[j] = static_cast<float>(v);
      p[j] = static_cast<float>(p[j] - learning_rate * v);
    }
    return;
  }
  const double c1 = 1.0 - std::pow(o.adam_beta1, static_cast<double>(step_));
  const double c2 = 1.0 - std::pow(o.adam_beta2, static_cast<double>(step_));
  for (size_t j = 0; j < p.size(); ++j) {
    const double d = grad[j] * inv_nodes + o.weight_decay * p[j];
    const double m = o.adam_beta1 * state1_[j] + (1 - o.adam_beta1) * d;
    const double v = o.adam_beta2 * state2_[j] + (1 - o.adam_beta2) * d * d;
    state1_[j] = static_cast<float>(m);
    state2_[j] = static_cast<float>(v);
    p[j] = static_cast<float>(p[j] - learning_rate * (m / c1) /
                                         (std::sqrt(v / c2) + o.adam_epsilon));
  }
}

}  // namespace colmap_gcn

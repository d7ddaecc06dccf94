#include "gcn/gcn_model.h"

#include <cmath>
#include <random>

#include "util/error.h"

namespace colmap_gcn {

bool GcnShape::Check() const {
  if (input_dim <= 0 || fc_dim <= 0 || gcn_dims.empty()) return false;
  for (int dim : gcn_dims) {
    if (dim <= 0) return false;
  }
  return true;
}

GcnParameterLayout::GcnParameterLayout(const GcnShape& shape) {
  size_t offset = 0;
  for (int l = 0; l < shape.NumGcnLayers(); ++l) {
    gcn_weight.push_back(offset);
    offset +=
        static_cast<size_t>(2) * shape.LayerInputDim(l) * shape.gcn_dims[l];
    gcn_bias.push_back(offset);
    offset += shape.gcn_dims[l];
  }
  fc1_weight = offset;
  offset +=
      static_cast<size_t>(shape.gcn_dims.empty() ? 0 : shape.gcn_dims.back()) *
      shape.fc_dim;
  fc1_bias = offset;
  offset += shape.fc_dim;
  prelu = offset;
  offset += shape.fc_dim;
  fc2_weight = offset;
  offset += shape.fc_dim;
  fc2_bias = offset;
  offset += 1;
  size = offset;
}

void GcnModel::Check() const {
  if (!shape.Check()) ThrowError("invalid GCN network shape");
  if (input_shift.size() != shape.input_dim ||
      input_scale.size() != shape.input_dim) {
    ThrowError("GCN input standardisation has size ",
               input_shift.size(),
               "/",
               input_scale.size(),
               ", expected ",
               shape.input_dim);
  }
  if (!(params.Shape() == shape) ||
      params.Size() != GcnParameterLayout(shape).size) {
    ThrowError("GCN parameters do not match the network shape");
  }
}

void GcnModel::CheckEmbeddingDimension(int dim) const {
  if (dim != shape.input_dim) {
    ThrowError("the GCN model expects ",
               shape.input_dim,
               "-dimensional embeddings (type '",
               embedding.type,
               "') but got ",
               dim,
               "-dimensional ones");
  }
}

RowMatrix<float> GcnModel::NodeFeatures(
    const QuerySubgraph& subgraph, const EmbeddingMatrix& embeddings) const {
  CheckEmbeddingDimension(static_cast<int>(embeddings.cols()));
  RowMatrix<float> x = QesFeatures(subgraph, embeddings);
  for (int i = 0; i < x.rows(); ++i) {
    x.row(i) = ((x.row(i) - input_shift.transpose()).array() *
                input_scale.transpose().array())
                   .matrix();
  }
  return x;
}

GcnModel InitializeGcnModel(const GcnShape& shape,
                            GcnAggregation aggregation,
                            uint32_t seed) {
  if (!shape.Check()) ThrowError("invalid GCN network shape");
  GcnModel model;
  model.shape = shape;
  model.aggregation = aggregation;
  model.input_shift = Eigen::VectorXf::Zero(shape.input_dim);
  model.input_scale = Eigen::VectorXf::Ones(shape.input_dim);
  model.params = GcnParameters<float>(shape);
  model.embedding.dim = shape.input_dim;

  std::mt19937 rng(seed);
  auto xavier = [&rng](float* data, int fan_in, int fan_out) {
    const float bound = std::sqrt(6.f / static_cast<float>(fan_in + fan_out));
    std::uniform_real_distribution<float> uniform(-bound, bound);
    for (long i = 0; i < static_cast<long>(fan_in) * fan_out; ++i) {
      data[i] = uniform(rng);
    }
  };
  for (int l = 0; l < shape.NumGcnLayers(); ++l) {
    auto w = model.params.GcnWeight(l);
    xavier(w.data(), static_cast<int>(w.rows()), static_cast<int>(w.cols()));
  }
  auto fc1 = model.params.Fc1Weight();
  xavier(
      fc1.data(), static_cast<int>(fc1.rows()), static_cast<int>(fc1.cols()));
  model.params.Prelu().setConstant(0.25f);
  xavier(model.params.Fc2Weight().data(), shape.fc_dim, 1);
  return model;
}

}  // namespace colmap_gcn

#include "gcn/gcn_model.h"

#include <cmath>
#include <random>

#include "util/error.h"
#include "util/option_check.h"

namespace colmap_gcn {

void GcnShape::Check() const {
  CHECK_OPTION_GE(input_dim, 1);
  CHECK_OPTION(
      gcn_dims,
      !gcn_dims.empty() && std::all_of(gcn_dims.begin(),
                                       gcn_dims.end(),
                                       [](int dim) { return dim > 0; }),
      "be a non-empty list of positive sizes");
  CHECK_OPTION_GE(fc_dim, 1);
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
  try {
    shape.Check();
  } catch (const Error& error) {
    ThrowError("invalid GCN network shape: ", error.what());
  }
  if (input_shift.size() != shape.input_dim ||
      input_scale.size() != shape.input_dim) {
    ThrowError("GCN input standardisation has size ",
               input_shift.size(),
               "/",
               input_scale.size(),
               ", expected ",
               shape.input_dim);
  }
  const bool differences = QesUsesEmbeddingDifferences(structure_features);
  if (differences ? DifferenceDim() < 1
                  : shape.input_dim != QesStructureDim(structure_features)) {
    ThrowError("GCN network input ",
               shape.input_dim,
               " does not fit ",
               QesStructureFeaturesName(structure_features),
               " structural features",
               differences ? " after the embedding differences" : "");
  }
  if (EmbeddingDim() < 1) {
    ThrowError("GCN model reads ", EmbeddingDim(), "-dimensional embeddings");
  }
  if (!(params.Shape() == shape) ||
      params.Size() != GcnParameterLayout(shape).size) {
    ThrowError("GCN parameters do not match the network shape");
  }
}

void GcnModel::CheckEmbeddingDimension(int dim) const {
  if (dim != EmbeddingDim()) {
    ThrowError("the GCN model ",
               source.empty() ? "" : source + " ",
               "expects ",
               EmbeddingDim(),
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
  RowMatrix<float> x = QesNodeFeatures(
      subgraph, embeddings, feature_scaling, structure_features);
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
  shape.Check();
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

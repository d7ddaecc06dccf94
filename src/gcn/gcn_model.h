#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "gcn/query_enclosing_subgraph.h"
#include "retrieval/embedding.h"

namespace colmap_gcn {

template <typename T>
using RowMatrix =
    Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
template <typename T>
using ColVector = Eigen::Matrix<T, Eigen::Dynamic, 1>;

// Network shape (paper Sec. 3.3, sizes of gcn_clustering): GCN layers
// Y = ReLU([X || G X] W + b) with output sizes gcn_dims, then
// FC(gcn_dims.back() -> fc_dim) + PReLU (per channel), then FC(fc_dim -> 1)
// whose output is the logit of "matchable".
struct GcnShape {
  int input_dim = 256;
  std::vector<int> gcn_dims = {512, 512, 256, 256};
  int fc_dim = 256;

  // Throws OptionError naming the first invalid field.
  void Check() const;
  int NumGcnLayers() const { return static_cast<int>(gcn_dims.size()); }
  int LayerInputDim(int layer) const {
    return layer == 0 ? input_dim : gcn_dims[layer - 1];
  }
  bool operator==(const GcnShape& other) const {
    return input_dim == other.input_dim && gcn_dims == other.gcn_dims &&
           fc_dim == other.fc_dim;
  }
};

// Offsets of the parameter groups in one flat array.
struct GcnParameterLayout {
  std::vector<size_t> gcn_weight;  // layer l: (2 in_l) x out_l, row-major
  std::vector<size_t> gcn_bias;    // out_l
  size_t fc1_weight = 0;           // gcn_dims.back() x fc_dim, row-major
  size_t fc1_bias = 0;             // fc_dim
  size_t prelu = 0;                // fc_dim (PReLU slopes)
  size_t fc2_weight = 0;           // fc_dim
  size_t fc2_bias = 0;             // 1
  size_t size = 0;

  explicit GcnParameterLayout(const GcnShape& shape);
};

// All trainable parameters in one flat array (so optimisers, gradient
// accumulation and serialisation are plain loops), with typed views. Weight
// matrices are stored input-major (x W), i.e. transposed w.r.t. torch's
// nn.Linear.weight; a GCN layer's W stacks W_self (rows 0..in-1, applied to
// X) over W_agg (rows in..2in-1, applied to G X).
template <typename T>
class GcnParameters {
 public:
  typedef Eigen::Map<RowMatrix<T>> MatrixMap;
  typedef Eigen::Map<const RowMatrix<T>> ConstMatrixMap;
  typedef Eigen::Map<ColVector<T>> VectorMap;
  typedef Eigen::Map<const ColVector<T>> ConstVectorMap;

  GcnParameters() : layout_(shape_) {}
  explicit GcnParameters(const GcnShape& shape)
      : shape_(shape), layout_(shape), values_(layout_.size, T(0)) {}

  const GcnShape& Shape() const { return shape_; }
  const GcnParameterLayout& Layout() const { return layout_; }
  std::vector<T>& Values() { return values_; }
  const std::vector<T>& Values() const { return values_; }
  size_t Size() const { return values_.size(); }

  MatrixMap GcnWeight(int l) {
    return MatrixMap(values_.data() + layout_.gcn_weight[l],
                     2 * shape_.LayerInputDim(l),
                     shape_.gcn_dims[l]);
  }
  ConstMatrixMap GcnWeight(int l) const {
    return ConstMatrixMap(values_.data() + layout_.gcn_weight[l],
                          2 * shape_.LayerInputDim(l),
                          shape_.gcn_dims[l]);
  }
  VectorMap GcnBias(int l) {
    return VectorMap(values_.data() + layout_.gcn_bias[l], shape_.gcn_dims[l]);
  }
  ConstVectorMap GcnBias(int l) const {
    return ConstVectorMap(values_.data() + layout_.gcn_bias[l],
                          shape_.gcn_dims[l]);
  }
  MatrixMap Fc1Weight() {
    return MatrixMap(values_.data() + layout_.fc1_weight,
                     shape_.gcn_dims.back(),
                     shape_.fc_dim);
  }
  ConstMatrixMap Fc1Weight() const {
    return ConstMatrixMap(values_.data() + layout_.fc1_weight,
                          shape_.gcn_dims.back(),
                          shape_.fc_dim);
  }
  VectorMap Fc1Bias() { return Vec(layout_.fc1_bias, shape_.fc_dim); }
  ConstVectorMap Fc1Bias() const {
    return Vec(layout_.fc1_bias, shape_.fc_dim);
  }
  VectorMap Prelu() { return Vec(layout_.prelu, shape_.fc_dim); }
  ConstVectorMap Prelu() const { return Vec(layout_.prelu, shape_.fc_dim); }
  VectorMap Fc2Weight() { return Vec(layout_.fc2_weight, shape_.fc_dim); }
  ConstVectorMap Fc2Weight() const {
    return Vec(layout_.fc2_weight, shape_.fc_dim);
  }
  T& Fc2Bias() { return values_[layout_.fc2_bias]; }
  T Fc2Bias() const { return values_[layout_.fc2_bias]; }

  template <typename U>
  GcnParameters<U> Cast() const {
    GcnParameters<U> out(shape_);
    for (size_t i = 0; i < values_.size(); ++i) {
      out.Values()[i] = static_cast<U>(values_[i]);
    }
    return out;
  }

  void SetZero() { std::fill(values_.begin(), values_.end(), T(0)); }

 private:
  VectorMap Vec(size_t offset, int size) {
    return VectorMap(values_.data() + offset, size);
  }
  ConstVectorMap Vec(size_t offset, int size) const {
    return ConstVectorMap(values_.data() + offset, size);
  }

  GcnShape shape_;
  GcnParameterLayout layout_;
  std::vector<T> values_;
};

// Training labels and recommended test-time settings stored with a model.
struct GcnModelInfo {
  float tau_mo = 0.25f;  // mesh-overlap threshold used for the labels
  float tau_ct = 0.15f;  // common-track threshold used for the labels
  int test_k1 = 100;
  int test_k2 = 5;
  int test_u = 5;
  float threshold = 0.5f;  // decision threshold on sigmoid(logit)
  std::string notes;       // free text, e.g. training data summary
};

struct GcnModel {
  GcnShape shape;
  GcnAggregation aggregation = GcnAggregation::kSymmetric;
  // Per-query scaling of the node features, before the standardisation.
  QesFeatureScaling feature_scaling = QesFeatureScaling::kNone;
  // Structural node features: the network input is [x_v - x_q | structure],
  // input_dim = DifferenceDim() + QesStructureDim(structure_features), where
  // DifferenceDim() is the embedding dimension D, or 0 for kReciprocalOnly.
  QesStructureFeatures structure_features = QesStructureFeatures::kNone;
  // Fixed input standardisation x' = (x - input_shift) .* input_scale applied
  // to the QES node features (replaces gcn_clustering's BatchNorm1d without
  // affine; estimated once from training subgraphs). Size input_dim.
  Eigen::VectorXf input_shift;
  Eigen::VectorXf input_scale;
  GcnParameters<float> params;
  GcnEmbeddingConfig embedding;
  GcnModelInfo info;
  // The file the model was read from, for messages ("" for a model made in
  // memory); not stored in the file.
  std::string source;

  // Throws Error if the sizes are inconsistent.
  void Check() const;
  // Number of network inputs that are embedding differences x_v - x_q.
  int DifferenceDim() const {
    return QesUsesEmbeddingDifferences(structure_features)
               ? shape.input_dim - QesStructureDim(structure_features)
               : 0;
  }
  // Dimension D of the embeddings the model reads.
  int EmbeddingDim() const {
    return QesUsesEmbeddingDifferences(structure_features) ? DifferenceDim()
                                                           : embedding.dim;
  }
  // Throws a one-line Error unless embeddings of dimension `dim` fit.
  void CheckEmbeddingDimension(int dim) const;
  // Standardised node features of a QES.
  RowMatrix<float> NodeFeatures(const QuerySubgraph& subgraph,
                                const EmbeddingMatrix& embeddings) const;
};

// Xavier-uniform weights (as gcn_clustering's GraphConv; also used for the FC
// layers), zero biases, PReLU slopes 0.25 (torch's default), identity input
// standardisation. Deterministic given the seed.
GcnModel InitializeGcnModel(const GcnShape& shape,
                            GcnAggregation aggregation,
                            uint32_t seed);

}  // namespace colmap_gcn

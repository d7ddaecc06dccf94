#pragma once

#include "retrieval/kmeans.h"

namespace colmap_gcn {

struct PcaOptions {
  // Output dimension; capped by the rank of the centred samples (<= N - 1).
  int dim = 256;

  // Component i is scaled by 1 / sqrt(lambda_i + shrinkage * mean(lambda)).
  // 0 is full PCA-whitening. Full whitening of the very samples it was
  // estimated on to their full rank makes them all equidistant (the centred,
  // whitened Gram matrix is a projection), so a model trained on the target
  // database itself needs shrinkage > 0; see docs/retrieval.md.
  double shrinkage = 0.0;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// y = projection * (x - mean), projection: dim x input_dim with the
// whitening scales folded in.
struct PcaWhitening {
  Eigen::RowVectorXf mean;
  FloatMatrix projection;
  Eigen::VectorXf eigenvalues;  // of the kept components, decreasing

  int InputDim() const { return static_cast<int>(mean.size()); }
  int OutputDim() const { return static_cast<int>(projection.rows()); }

  // Rows of x projected (not normalised).
  FloatMatrix Apply(const FloatMatrix& x) const;
};

// PCA (with optional whitening) of the rows of samples. When there are fewer
// samples than dimensions (the usual case for 8192-D VLADs) the N x N Gram
// matrix is decomposed instead of the D x D covariance.
PcaWhitening TrainPcaWhitening(const FloatMatrix& samples,
                               const PcaOptions& options);

}  // namespace colmap_gcn

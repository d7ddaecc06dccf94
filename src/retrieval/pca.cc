#include "retrieval/pca.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "math/dense_product.h"
#include "util/error.h"
#include "util/option_check.h"

namespace colmap_gcn {

void PcaOptions::Check() const {
  CHECK_OPTION_GE(dim, 1);
  CHECK_OPTION_GE(shrinkage, 0.0);
}

FloatMatrix PcaWhitening::Apply(const FloatMatrix& x) const {
  THROW_CHECK(x.cols() == InputDim());
  const FloatMatrix centred = x.rowwise() - mean;
  FloatMatrix y(x.rows(), OutputDim());
  MultiplyABt(centred.data(),
              static_cast<int>(centred.rows()),
              projection.data(),
              OutputDim(),
              InputDim(),
              y.data());
  return y;
}

PcaWhitening TrainPcaWhitening(const FloatMatrix& samples,
                               const PcaOptions& options) {
  options.Check();
  const int num_samples = static_cast<int>(samples.rows());
  const int input_dim = static_cast<int>(samples.cols());
  if (num_samples < 2) {
    ThrowError("PCA needs at least 2 samples, got ", num_samples);
  }
  PcaWhitening pca;
  pca.mean = samples.colwise().mean();
  const Eigen::MatrixXd centred = (samples.rowwise() - pca.mean).cast<double>();

  // Eigen-decomposition in double, components sorted by decreasing variance;
  // directions as columns of a D x r matrix.
  Eigen::VectorXd eigenvalues;
  Eigen::MatrixXd directions;
  if (num_samples < input_dim) {
    const Eigen::MatrixXd gram = centred * centred.transpose() / num_samples;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(gram);
    eigenvalues = solver.eigenvalues().reverse();
    const Eigen::MatrixXd u = solver.eigenvectors().rowwise().reverse();
    // v_i = X^T u_i / sqrt(N lambda_i) has unit norm.
    directions = centred.transpose() * u;
    for (int i = 0; i < directions.cols(); ++i) {
      const double norm = directions.col(i).norm();
      if (norm > 0) directions.col(i) /= norm;
    }
  } else {
    const Eigen::MatrixXd covariance =
        centred.transpose() * centred / num_samples;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
    eigenvalues = solver.eigenvalues().reverse();
    directions = solver.eigenvectors().rowwise().reverse();
  }

  // Keep numerically non-zero components only (at most N - 1 exist).
  const double max_eigenvalue = std::max(0.0, eigenvalues(0));
  int rank = 0;
  while (rank < eigenvalues.size() && rank < num_samples - 1 &&
         eigenvalues(rank) > 1e-9 * max_eigenvalue && eigenvalues(rank) > 0) {
    ++rank;
  }
  const int dim = std::min(options.dim, rank);
  if (dim == 0) {
    ThrowError("PCA: the samples are all identical");
  }
  const double mean_eigenvalue = eigenvalues.head(rank).mean();
  pca.projection.resize(dim, input_dim);
  pca.eigenvalues.resize(dim);
  for (int i = 0; i < dim; ++i) {
    // Deterministic sign: the largest-magnitude entry is positive.
    Eigen::Index argmax;
    directions.col(i).cwiseAbs().maxCoeff(&argmax);
    const double sign = directions(argmax, i) < 0 ? -1.0 : 1.0;
    const double scale =
        sign / std::sqrt(eigenvalues(i) + options.shrinkage * mean_eigenvalue);
    pca.projection.row(i) =
        (directions.col(i) * scale).transpose().cast<float>();
    pca.eigenvalues(i) = static_cast<float>(eigenvalues(i));
  }
  return pca;
}

}  // namespace colmap_gcn

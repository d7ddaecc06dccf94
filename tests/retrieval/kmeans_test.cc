#include "retrieval/kmeans.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "retrieval/pca.h"
#include "util/error.h"

namespace colmap_gcn {
namespace {

FloatMatrix Blobs(int per_blob, uint32_t seed, FloatMatrix* centres) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0, 0.05f);
  *centres = FloatMatrix(4, 3);
  *centres << 0, 0, 0, 5, 0, 0, 0, 5, 0, 0, 0, 5;
  FloatMatrix points(4 * per_blob, 3);
  for (int i = 0; i < points.rows(); ++i) {
    for (int c = 0; c < 3; ++c) {
      points(i, c) = (*centres)(i % 4, c) + noise(rng);
    }
  }
  return points;
}

TEST(KMeans, FindsSeparatedClustersIndependentOfThreads) {
  FloatMatrix truth;
  const FloatMatrix points = Blobs(5000, 1, &truth);  // > one chunk
  KMeansOptions options;
  options.num_clusters = 4;
  options.num_threads = 1;
  const FloatMatrix one = KMeans(points, options);
  options.num_threads = 3;
  const FloatMatrix three = KMeans(points, options);
  EXPECT_EQ(one, three);  // bit-identical
  std::set<int> matched;
  for (int t = 0; t < 4; ++t) {
    for (int c = 0; c < 4; ++c) {
      if ((one.row(c) - truth.row(t)).norm() < 0.05) matched.insert(c);
    }
  }
  EXPECT_EQ(matched.size(), 4u);
  options.seed = 99;
  EXPECT_EQ(KMeans(points, options).rows(), 4);
}

TEST(KMeans, DegenerateInputs) {
  FloatMatrix same = FloatMatrix::Ones(10, 2);
  KMeansOptions options;
  options.num_clusters = 3;
  const FloatMatrix centres = KMeans(same, options);
  EXPECT_EQ(centres, FloatMatrix::Ones(3, 2));
  options.num_clusters = 11;
  EXPECT_THROW(KMeans(same, options), Error);
}

TEST(AssignToNearestCenter, TiesGoToLowerIndex) {
  FloatMatrix centres(2, 1);
  centres << -1, 1;
  FloatMatrix points(3, 1);
  points << 0, -0.5, 2;
  EXPECT_EQ(AssignToNearestCenter(points, centres),
            (std::vector<int>{0, 0, 1}));
}

TEST(Pca, WhitenedTrainingDataHasIdentityCovariance) {
  std::mt19937 rng(4);
  std::normal_distribution<float> normal;
  FloatMatrix samples(200, 10);
  for (int i = 0; i < samples.size(); ++i) samples.data()[i] = normal(rng);
  samples.col(0) *= 10;  // anisotropic
  samples.col(3) *= 3;
  PcaOptions options;
  options.dim = 4;
  const PcaWhitening pca = TrainPcaWhitening(samples, options);
  ASSERT_EQ(pca.OutputDim(), 4);
  const FloatMatrix y = pca.Apply(samples);
  const Eigen::MatrixXf covariance = y.transpose() * y / y.rows();
  EXPECT_TRUE(covariance.isApprox(Eigen::MatrixXf::Identity(4, 4), 1e-3))
      << covariance;
  EXPECT_GT(pca.eigenvalues(0), pca.eigenvalues(1));
}

TEST(Pca, FewSamplesUseGramTrickAndCapAtNMinusOne) {
  std::mt19937 rng(8);
  std::normal_distribution<float> normal;
  FloatMatrix samples(6, 50);
  for (int i = 0; i < samples.size(); ++i) samples.data()[i] = normal(rng);
  PcaOptions options;
  options.dim = 256;
  options.shrinkage = 1e6;  // ~ plain PCA: distances preserved up to scale
  const PcaWhitening pca = TrainPcaWhitening(samples, options);
  EXPECT_EQ(pca.OutputDim(), 5);
  const FloatMatrix y = pca.Apply(samples);
  const double scale =
      (y.row(0) - y.row(1)).norm() / (samples.row(0) - samples.row(1)).norm();
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      EXPECT_NEAR((y.row(i) - y.row(j)).norm(),
                  scale * (samples.row(i) - samples.row(j)).norm(),
                  1e-3 * scale * 10);
    }
  }
  // Projection rows are orthogonal directions.
  const Eigen::MatrixXf gram = pca.projection * pca.projection.transpose();
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < i; ++j) EXPECT_NEAR(gram(i, j), 0, 1e-3 * gram(i, i));
  }
  EXPECT_THROW(TrainPcaWhitening(FloatMatrix::Ones(1, 4), options), Error);
}

}  // namespace
}  // namespace colmap_gcn

#include "math/sgemm.h"

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>

namespace colmap_gcn {
namespace {

template <typename T>
using RowMatrix =
    Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

TEST(Sgemm, MatchesEigenWithStridesAndBeta) {
  std::mt19937 rng(3);
  for (const auto& [m, k, n] : std::vector<std::array<int, 3>>{
           {1, 1, 1}, {7, 300, 45}, {130, 70, 33}, {13, 513, 64}}) {
    RowMatrix<float> a = RowMatrix<float>::Random(m, k);
    RowMatrix<float> bt = RowMatrix<float>::Random(n, k);  // B transposed
    RowMatrix<float> c = RowMatrix<float>::Random(m, n);
    const RowMatrix<float> expected = a * bt.transpose() + 0.5f * c;
    Sgemm(RowMajorView(a.data(), m, k, k),
          RowMajorView(bt.data(), n, k, k).Transposed(),
          0.5f,
          c.data(),
          n);
    EXPECT_LT((c - expected).cwiseAbs().maxCoeff(), 1e-4f * std::sqrt(k));
  }
}

TEST(Sgemm, PackedBEqualsUnpackedBitForBit) {
  // Row-major and strided A, several kKc slices, ragged panels.
  for (const auto& [m, k, n] : std::vector<std::array<int, 3>>{
           {1, 1, 1}, {13, 513, 64}, {130, 1024, 45}, {184, 600, 512}}) {
    const RowMatrix<float> a = RowMatrix<float>::Random(m, k);
    const RowMatrix<float> b = RowMatrix<float>::Random(k, n);
    const RowMatrix<float> c0 = RowMatrix<float>::Random(m, n);
    const PackedMatrix packed(RowMajorView(b.data(), k, n, n));
    EXPECT_EQ(packed.Rows(), k);
    EXPECT_EQ(packed.Cols(), n);
    for (const float beta : {0.f, 1.f, 0.5f}) {
      RowMatrix<float> expected = c0;
      RowMatrix<float> actual = c0;
      Sgemm(RowMajorView(a.data(), m, k, k),
            RowMajorView(b.data(), k, n, n),
            beta,
            expected.data(),
            n);
      Sgemm(RowMajorView(a.data(), m, k, k), packed, beta, actual.data(), n);
      EXPECT_EQ(actual, expected) << m << "x" << k << "x" << n;
    }
  }
}

TEST(Sgemm, AxpyAndReluMatchScalarLoops) {
  for (const int n : {1, 7, 16, 33, 512}) {
    const Eigen::VectorXf x = Eigen::VectorXf::Random(n);
    Eigen::VectorXf y = Eigen::VectorXf::Random(n);
    Eigen::VectorXf expected = y;
    for (int j = 0; j < n; ++j) expected(j) += 0.3f * x(j);
    Axpy(n, 0.3f, x.data(), y.data());
    // The vector kernels' scalar tails may be contracted to FMA.
    EXPECT_LT((y - expected).cwiseAbs().maxCoeff(), 1e-6f);
    const Eigen::VectorXf before = y;
    Relu(n, y.data());
    EXPECT_EQ(y, before.cwiseMax(0.f));
    EXPECT_GE(y.minCoeff(), 0.f);
  }
}

}  // namespace
}  // namespace colmap_gcn

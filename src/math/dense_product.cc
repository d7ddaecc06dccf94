#include "math/dense_product.h"

#include <Eigen/Core>

namespace colmap_gcn {

#ifdef COLMAP_GCN_HAVE_AVX2_KERNEL
// Defined in dense_product_avx2.cc, compiled with -mavx2 -mfma.
void MultiplyABtAvx2(
    const float* a, int m, const float* b, int n, int d, float* c);
#endif

namespace {

void MultiplyABtPortable(
    const float* a, int m, const float* b, int n, int d, float* c) {
  typedef Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
      Matrix;
  const Eigen::Map<const Matrix> a_map(a, m, d);
  const Eigen::Map<const Matrix> b_map(b, n, d);
  Eigen::Map<Matrix> c_map(c, m, n);
  c_map.noalias() = a_map * b_map.transpose();
}

bool UseAvx2() {
#ifdef COLMAP_GCN_HAVE_AVX2_KERNEL
  static const bool supported =
      __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return supported;
#else
  return false;
#endif
}

}  // namespace

void MultiplyABt(
    const float* a, int m, const float* b, int n, int d, float* c) {
  if (m == 0 || n == 0) {
    return;
  }
#ifdef COLMAP_GCN_HAVE_AVX2_KERNEL
  if (UseAvx2()) {
    MultiplyABtAvx2(a, m, b, n, d, c);
    return;
  }
#endif
  MultiplyABtPortable(a, m, b, n, d, c);
}

const char* DenseProductKernelName() {
  return UseAvx2() ? "avx2-fma" : "portable";
}

}  // namespace colmap_gcn

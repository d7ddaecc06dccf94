// The AVX2+FMA build of MultiplyABt. This file is compiled with -mavx2
// -mfma while the rest of the library is not, so every Eigen symbol
// instantiated here must differ from the portable ones: otherwise the linker
// may keep the AVX2 copy of a shared inline template for portable callers
// (SIGILL on older CPUs) or the portable copy for this kernel (no speed-up).
// Renaming Eigen's namespace for this translation unit guarantees that.
// Nothing else from the project may be included here.
#define Eigen colmap_gcn_eigen_avx2
#include <Eigen/Core>

namespace colmap_gcn {

void MultiplyABtAvx2(
    const float* a, int m, const float* b, int n, int d, float* c) {
  typedef Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
      Matrix;
  const Eigen::Map<const Matrix> a_map(a, m, d);
  const Eigen::Map<const Matrix> b_map(b, n, d);
  Eigen::Map<Matrix> c_map(c, m, n);
  c_map.noalias() = a_map * b_map.transpose();
}

}  // namespace colmap_gcn

#pragma once

#include <string>

namespace colmap_gcn {

// A strided view of a float matrix: element (r, c) is at
// data[r * row_stride + c * col_stride]. A transposed row-major matrix is the
// same memory with the strides swapped.
struct ConstMatrixView {
  const float* data = nullptr;
  int rows = 0;
  int cols = 0;
  long row_stride = 0;
  long col_stride = 1;

  ConstMatrixView Transposed() const {
    return {data, cols, rows, col_stride, row_stride};
  }
};

inline ConstMatrixView RowMajorView(const float* data,
                                    int rows,
                                    int cols,
                                    long stride) {
  return {data, rows, cols, stride, 1};
}

// C = A * B + beta * C with C row-major (leading dimension ldc), single
// threaded. The hot loops of the GCN: a packed, register-blocked kernel with
// AVX-512 / AVX2+FMA variants chosen at run time (the rest of the project is
// built for the baseline ISA; these kernels carry their own target attributes
// and use no Eigen code, so no inline function is compiled twice with
// different instruction sets). The result does not depend on the thread
// calling it; for fixed sizes and ISA it is bit-for-bit reproducible.
void Sgemm(const ConstMatrixView& a,
           const ConstMatrixView& b,
           float beta,
           float* c,
           long ldc);

// "avx512", "avx2" or "generic": the kernel Sgemm uses on this CPU.
std::string SgemmKernelName();

}  // namespace colmap_gcn

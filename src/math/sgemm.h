#pragma once

#include <string>
#include <vector>

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

// B packed once into the kernel's panel layout, for products of many
// different A with the same B (the GCN's weights): Sgemm(a, b) repacks B on
// every call, which for a 1024 x 512 weight matrix costs as much memory
// traffic as a small product. Bit-identical results to Sgemm(a, b).
class PackedMatrix {
 public:
  PackedMatrix() = default;
  explicit PackedMatrix(const ConstMatrixView& b);

  int Rows() const { return rows_; }
  int Cols() const { return cols_; }
  // The packed kKc-deep slice starting at row p0 (a multiple of kKc).
  const float* Slice(int p0) const;

 private:
  int rows_ = 0;
  int cols_ = 0;
  int num_panels_ = 0;
  int nr_ = 0;
  std::vector<float> data_;
};

// C = A * B + beta * C with a pre-packed B.
void Sgemm(const ConstMatrixView& a,
           const PackedMatrix& b,
           float beta,
           float* c,
           long ldc);

// y += w * x over n floats, and x = max(x, 0): the GCN's sparse
// aggregation and activation, with the same run-time ISA choice as Sgemm
// (the rest of the project is built for the baseline ISA). Element-wise:
// independent of the calling thread; equal to the scalar loops up to
// rounding (the kernels' tails may use FMA).
void Axpy(int n, float w, const float* x, float* y);
void Relu(long n, float* x);

// "avx512", "avx2" or "generic": the kernel Sgemm uses on this CPU.
std::string SgemmKernelName();

}  // namespace colmap_gcn

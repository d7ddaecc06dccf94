#include "math/sgemm.h"

#include <immintrin.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "util/error.h"

namespace colmap_gcn {
namespace {

// Blocking: a kKc-deep slice of B is packed into NR-wide panels (one panel,
// kKc x NR floats, stays in L1 while the micro-rows of an A block stream
// past); a kMc x kKc block of A is packed into MR-high micro-panels (L2).
constexpr int kKc = 256;
constexpr int kMc = 120;  // Multiple of every MR below.

// C(tile) += acc for the valid part of an MR x NR tile held in `tile`.
inline void AddTile(
    const float* tile, int nr, float* c, long ldc, int m_valid, int n_valid) {
  for (int r = 0; r < m_valid; ++r) {
    float* crow = c + r * ldc;
    const float* trow = tile + r * nr;
    for (int j = 0; j < n_valid; ++j) crow[j] += trow[j];
  }
}

__attribute__((target("avx512f"))) void KernelAvx512(int kc,
                                                     const float* a,
                                                     const float* b,
                                                     float* c,
                                                     long ldc,
                                                     int m_valid,
                                                     int n_valid) {
  constexpr int MR = 12;
  constexpr int NR = 32;
  __m512 acc[MR][2];
#pragma GCC unroll 12
  for (int r = 0; r < MR; ++r) {
    acc[r][0] = _mm512_setzero_ps();
    acc[r][1] = _mm512_setzero_ps();
  }
  for (int p = 0; p < kc; ++p) {
    const __m512 b0 = _mm512_loadu_ps(b + p * NR);
    const __m512 b1 = _mm512_loadu_ps(b + p * NR + 16);
    const float* ap = a + p * MR;
#pragma GCC unroll 12
    for (int r = 0; r < MR; ++r) {
      const __m512 av = _mm512_set1_ps(ap[r]);
      acc[r][0] = _mm512_fmadd_ps(av, b0, acc[r][0]);
      acc[r][1] = _mm512_fmadd_ps(av, b1, acc[r][1]);
    }
  }
  if (m_valid == MR && n_valid == NR) {
#pragma GCC unroll 12
    for (int r = 0; r < MR; ++r) {
      float* crow = c + r * ldc;
      _mm512_storeu_ps(crow, _mm512_add_ps(_mm512_loadu_ps(crow), acc[r][0]));
      _mm512_storeu_ps(crow + 16,
                       _mm512_add_ps(_mm512_loadu_ps(crow + 16), acc[r][1]));
    }
  } else {
    alignas(64) float tile[MR * NR];
    for (int r = 0; r < MR; ++r) {
      _mm512_storeu_ps(tile + r * NR, acc[r][0]);
      _mm512_storeu_ps(tile + r * NR + 16, acc[r][1]);
    }
    AddTile(tile, NR, c, ldc, m_valid, n_valid);
  }
}

__attribute__((target("avx2,fma"))) void KernelAvx2(int kc,
                                                    const float* a,
                                                    const float* b,
                                                    float* c,
                                                    long ldc,
                                                    int m_valid,
                                                    int n_valid) {
  constexpr int MR = 6;
  constexpr int NR = 16;
  __m256 acc[MR][2];
#pragma GCC unroll 6
  for (int r = 0; r < MR; ++r) {
    acc[r][0] = _mm256_setzero_ps();
    acc[r][1] = _mm256_setzero_ps();
  }
  for (int p = 0; p < kc; ++p) {
    const __m256 b0 = _mm256_loadu_ps(b + p * NR);
    const __m256 b1 = _mm256_loadu_ps(b + p * NR + 8);
    const float* ap = a + p * MR;
#pragma GCC unroll 6
    for (int r = 0; r < MR; ++r) {
      const __m256 av = _mm256_broadcast_ss(ap + r);
      acc[r][0] = _mm256_fmadd_ps(av, b0, acc[r][0]);
      acc[r][1] = _mm256_fmadd_ps(av, b1, acc[r][1]);
    }
  }
  alignas(32) float tile[MR * NR];
  for (int r = 0; r < MR; ++r) {
    _mm256_storeu_ps(tile + r * NR, acc[r][0]);
    _mm256_storeu_ps(tile + r * NR + 8, acc[r][1]);
  }
  AddTile(tile, NR, c, ldc, m_valid, n_valid);
}

void KernelGeneric(int kc,
                   const float* a,
                   const float* b,
                   float* c,
                   long ldc,
                   int m_valid,
                   int n_valid) {
  constexpr int MR = 4;
  constexpr int NR = 8;
  float tile[MR * NR] = {};
  for (int p = 0; p < kc; ++p) {
    for (int r = 0; r < MR; ++r) {
      const float av = a[p * MR + r];
      for (int j = 0; j < NR; ++j) tile[r * NR + j] += av * b[p * NR + j];
    }
  }
  AddTile(tile, NR, c, ldc, m_valid, n_valid);
}

__attribute__((target("avx512f"))) void AxpyAvx512(int n,
                                                   float w,
                                                   const float* x,
                                                   float* y) {
  const __m512 wv = _mm512_set1_ps(w);
  int j = 0;
  for (; j + 16 <= n; j += 16) {
    // Multiply, then add: the scalar loop's rounding.
    _mm512_storeu_ps(y + j,
                     _mm512_add_ps(_mm512_loadu_ps(y + j),
                                   _mm512_mul_ps(wv, _mm512_loadu_ps(x + j))));
  }
  for (; j < n; ++j) y[j] += w * x[j];
}

__attribute__((target("avx2"))) void AxpyAvx2(int n,
                                              float w,
                                              const float* x,
                                              float* y) {
  const __m256 wv = _mm256_set1_ps(w);
  int j = 0;
  for (; j + 8 <= n; j += 8) {
    _mm256_storeu_ps(y + j,
                     _mm256_add_ps(_mm256_loadu_ps(y + j),
                                   _mm256_mul_ps(wv, _mm256_loadu_ps(x + j))));
  }
  for (; j < n; ++j) y[j] += w * x[j];
}

void AxpyGeneric(int n, float w, const float* x, float* y) {
  for (int j = 0; j < n; ++j) y[j] += w * x[j];
}

// AVX2 also on AVX-512 machines: memory bound, and GCC 12 warns about
// _mm512_max_ps (-Wmaybe-uninitialized inside its own header).
__attribute__((target("avx2"))) void ReluAvx2(long n, float* x) {
  const __m256 zero = _mm256_setzero_ps();
  long j = 0;
  for (; j + 8 <= n; j += 8) {
    _mm256_storeu_ps(x + j, _mm256_max_ps(_mm256_loadu_ps(x + j), zero));
  }
  for (; j < n; ++j) x[j] = std::max(x[j], 0.f);
}

void ReluGeneric(long n, float* x) {
  for (long j = 0; j < n; ++j) x[j] = std::max(x[j], 0.f);
}

typedef void (*KernelFn)(
    int, const float*, const float*, float*, long, int, int);

struct Kernel {
  KernelFn fn;
  int mr;
  int nr;
  const char* name;
  void (*axpy)(int, float, const float*, float*);
  void (*relu)(long, float*);
};

Kernel SelectKernel() {
  const char* force = std::getenv("COLMAP_GCN_SGEMM");
  const std::string forced = force != nullptr ? force : "";
  __builtin_cpu_init();
  if ((forced.empty() || forced == "avx512") &&
      __builtin_cpu_supports("avx512f")) {
    return {&KernelAvx512, 12, 32, "avx512", &AxpyAvx512, &ReluAvx2};
  }
  if ((forced.empty() || forced == "avx512" || forced == "avx2") &&
      __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    return {&KernelAvx2, 6, 16, "avx2", &AxpyAvx2, &ReluAvx2};
  }
  return {&KernelGeneric, 4, 8, "generic", &AxpyGeneric, &ReluGeneric};
}

const Kernel& GetKernel() {
  static const Kernel kernel = SelectKernel();
  return kernel;
}

void PackA(const ConstMatrixView& a,
           int i0,
           int mc,
           int p0,
           int kc,
           int mr,
           float* dst) {
  for (int i = 0; i < mc; i += mr) {
    const int rows = std::min(mr, mc - i);
    float* panel = dst + static_cast<long>(i) * kc;
    if (a.col_stride == 1) {
      // Row-major A (the GCN's activations): read each row contiguously.
      for (int r = 0; r < rows; ++r) {
        const float* src = a.data + (i0 + i + r) * a.row_stride + p0;
        for (int p = 0; p < kc; ++p) panel[p * mr + r] = src[p];
      }
      for (int r = rows; r < mr; ++r) {
        for (int p = 0; p < kc; ++p) panel[p * mr + r] = 0.f;
      }
      continue;
    }
    for (int p = 0; p < kc; ++p) {
      const float* src =
          a.data + (i0 + i) * a.row_stride + (p0 + p) * a.col_stride;
      float* out = panel + p * mr;
      int r = 0;
      for (; r < rows; ++r) out[r] = src[r * a.row_stride];
      for (; r < mr; ++r) out[r] = 0.f;
    }
  }
}

void PackB(const ConstMatrixView& b, int p0, int kc, int nr, float* dst) {
  const int n = b.cols;
  const int num_panels = (n + nr - 1) / nr;
  for (int jp = 0; jp < num_panels; ++jp) {
    const int cols = std::min(nr, n - jp * nr);
    float* panel = dst + static_cast<long>(jp) * kc * nr;
    for (int p = 0; p < kc; ++p) {
      const float* src =
          b.data + (p0 + p) * b.row_stride + jp * nr * b.col_stride;
      float* out = panel + p * nr;
      int j = 0;
      if (b.col_stride == 1) {
        std::memcpy(out, src, sizeof(float) * cols);
        j = cols;
      } else {
        for (; j < cols; ++j) out[j] = src[j * b.col_stride];
      }
      for (; j < nr; ++j) out[j] = 0.f;
    }
  }
}

void ScaleC(int m, int n, float beta, float* c, long ldc) {
  if (beta == 1.f) return;
  for (int i = 0; i < m; ++i) {
    float* row = c + i * ldc;
    if (beta == 0.f) {
      std::fill(row, row + n, 0.f);
    } else {
      for (int j = 0; j < n; ++j) row[j] *= beta;
    }
  }
}

// C += A[:, p0:p0+kc] * (one packed kc-deep slice of B).
void MultiplySlice(const ConstMatrixView& a,
                   int p0,
                   int kc,
                   const float* packed_b,
                   int n,
                   float* c,
                   long ldc) {
  const Kernel& kernel = GetKernel();
  const int m = a.rows;
  const int num_panels = (n + kernel.nr - 1) / kernel.nr;
  thread_local std::vector<float> packed_a;
  packed_a.resize(static_cast<size_t>(kMc) * kKc);
  for (int i0 = 0; i0 < m; i0 += kMc) {
    const int mc = std::min(kMc, m - i0);
    PackA(a, i0, mc, p0, kc, kernel.mr, packed_a.data());
    for (int jp = 0; jp < num_panels; ++jp) {
      const float* bp = packed_b + static_cast<long>(jp) * kc * kernel.nr;
      const int n_valid = std::min(kernel.nr, n - jp * kernel.nr);
      for (int i = 0; i < mc; i += kernel.mr) {
        kernel.fn(kc,
                  packed_a.data() + static_cast<long>(i) * kc,
                  bp,
                  c + (i0 + i) * ldc + jp * kernel.nr,
                  ldc,
                  std::min(kernel.mr, mc - i),
                  n_valid);
      }
    }
  }
}

}  // namespace

void Sgemm(const ConstMatrixView& a,
           const ConstMatrixView& b,
           float beta,
           float* c,
           long ldc) {
  THROW_CHECK(a.cols == b.rows);
  const int m = a.rows;
  const int n = b.cols;
  const int k = a.cols;
  ScaleC(m, n, beta, c, ldc);
  if (m == 0 || n == 0 || k == 0) return;

  const Kernel& kernel = GetKernel();
  const int num_panels = (n + kernel.nr - 1) / kernel.nr;
  thread_local std::vector<float> packed_b;
  packed_b.resize(static_cast<size_t>(num_panels) * kernel.nr * kKc);
  for (int p0 = 0; p0 < k; p0 += kKc) {
    const int kc = std::min(kKc, k - p0);
    PackB(b, p0, kc, kernel.nr, packed_b.data());
    MultiplySlice(a, p0, kc, packed_b.data(), n, c, ldc);
  }
}

PackedMatrix::PackedMatrix(const ConstMatrixView& b)
    : rows_(b.rows), cols_(b.cols), nr_(GetKernel().nr) {
  num_panels_ = (cols_ + nr_ - 1) / nr_;
  data_.resize(static_cast<size_t>(rows_) * num_panels_ * nr_);
  for (int p0 = 0; p0 < rows_; p0 += kKc) {
    PackB(b,
          p0,
          std::min(kKc, rows_ - p0),
          nr_,
          data_.data() + static_cast<long>(p0) * num_panels_ * nr_);
  }
}

const float* PackedMatrix::Slice(int p0) const {
  return data_.data() + static_cast<long>(p0) * num_panels_ * nr_;
}

void Sgemm(const ConstMatrixView& a,
           const PackedMatrix& b,
           float beta,
           float* c,
           long ldc) {
  THROW_CHECK(a.cols == b.Rows());
  const int m = a.rows;
  const int n = b.Cols();
  const int k = a.cols;
  ScaleC(m, n, beta, c, ldc);
  if (m == 0 || n == 0 || k == 0) return;
  for (int p0 = 0; p0 < k; p0 += kKc) {
    MultiplySlice(a, p0, std::min(kKc, k - p0), b.Slice(p0), n, c, ldc);
  }
}

void Axpy(int n, float w, const float* x, float* y) {
  GetKernel().axpy(n, w, x, y);
}

void Relu(long n, float* x) { GetKernel().relu(n, x); }

std::string SgemmKernelName() { return GetKernel().name; }

}  // namespace colmap_gcn

#include "gcn/sgemm.h"

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

typedef void (*KernelFn)(
    int, const float*, const float*, float*, long, int, int);

struct Kernel {
  KernelFn fn;
  int mr;
  int nr;
  const char* name;
};

Kernel SelectKernel() {
  const char* force = std::getenv("COLMAP_GCN_SGEMM");
  const std::string forced = force != nullptr ? force : "";
  __builtin_cpu_init();
  if ((forced.empty() || forced == "avx512") &&
      __builtin_cpu_supports("avx512f")) {
    return {&KernelAvx512, 12, 32, "avx512"};
  }
  if ((forced.empty() || forced == "avx512" || forced == "avx2") &&
      __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    return {&KernelAvx2, 6, 16, "avx2"};
  }
  return {&KernelGeneric, 4, 8, "generic"};
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
  if (beta != 1.f) {
    for (int i = 0; i < m; ++i) {
      float* row = c + i * ldc;
      if (beta == 0.f) {
        std::fill(row, row + n, 0.f);
      } else {
        for (int j = 0; j < n; ++j) row[j] *= beta;
      }
    }
  }
  if (m == 0 || n == 0 || k == 0) return;

  const Kernel& kernel = GetKernel();
  const int num_panels = (n + kernel.nr - 1) / kernel.nr;
  thread_local std::vector<float> packed_a;
  thread_local std::vector<float> packed_b;
  packed_a.resize(static_cast<size_t>(kMc) * kKc);
  packed_b.resize(static_cast<size_t>(num_panels) * kernel.nr * kKc);

  for (int p0 = 0; p0 < k; p0 += kKc) {
    const int kc = std::min(kKc, k - p0);
    PackB(b, p0, kc, kernel.nr, packed_b.data());
    for (int i0 = 0; i0 < m; i0 += kMc) {
      const int mc = std::min(kMc, m - i0);
      PackA(a, i0, mc, p0, kc, kernel.mr, packed_a.data());
      for (int jp = 0; jp < num_panels; ++jp) {
        const float* bp =
            packed_b.data() + static_cast<long>(jp) * kc * kernel.nr;
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
}

std::string SgemmKernelName() { return GetKernel().name; }

}  // namespace colmap_gcn

#pragma once

namespace colmap_gcn {

// C = A * B^T for row-major float matrices A (m x d), B (n x d), C (m x n),
// all contiguous. The kernel behind the exact kNN and the VLAD assignment.
// Uses an AVX2+FMA build of Eigen's GEMM when the CPU supports it, else the
// portable build. For given shapes the result is bit-identical on every call
// (no threading inside), which keeps the kNN independent of thread count.
void MultiplyABt(const float* a, int m, const float* b, int n, int d, float* c);

// Which kernel MultiplyABt uses on this machine: "avx2-fma" or "portable".
const char* DenseProductKernelName();

}  // namespace colmap_gcn

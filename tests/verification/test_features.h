#pragma once

// Synthetic SIFT-like descriptors and a two-camera scene for the
// verification tests.

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "scene/database.h"
#include "util/random.h"

namespace colmap_gcn {
namespace test {

// Non-negative, norm ~512, uint8: as COLMAP stores SIFT descriptors.
inline Eigen::Matrix<float, 1, 128> RandomDescriptorDirection(uint64_t* state) {
  Eigen::Matrix<float, 1, 128> v;
  for (int d = 0; d < 128; ++d) {
    v(d) = static_cast<float>(SplitMix64(state) % 1000) / 1000.0f;
  }
  return v.normalized();
}

inline void SetDescriptor(const Eigen::Matrix<float, 1, 128>& direction,
                          FeatureDescriptors* descriptors,
                          Eigen::Index row) {
  const Eigen::Matrix<float, 1, 128> v = direction.normalized() * 512.0f;
  for (int d = 0; d < 128; ++d) {
    (*descriptors)(row, d) = static_cast<uint8_t>(
        std::min(255.0f, std::max(0.0f, std::round(v(d)))));
  }
}

// A small perturbation of a descriptor direction (another view of the same
// point).
inline Eigen::Matrix<float, 1, 128> Perturbed(
    const Eigen::Matrix<float, 1, 128>& direction,
    double amount,
    uint64_t* state) {
  Eigen::Matrix<float, 1, 128> v = direction;
  for (int d = 0; d < 128; ++d) {
    v(d) += static_cast<float>(
        amount * ((SplitMix64(state) % 2001) / 1000.0 - 1.0) / std::sqrt(128));
    v(d) = std::max(0.0f, v(d));
  }
  return v.normalized();
}

}  // namespace test
}  // namespace colmap_gcn

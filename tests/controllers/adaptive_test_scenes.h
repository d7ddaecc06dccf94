#pragma once

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <vector>

#include "controllers/adaptive_pairing.h"

namespace colmap_gcn {
namespace test {

// Simulated collections for the adaptive loop's unit tests: image ids,
// scored candidates and the verification COLMAP would report.

// A ring of images: neighbours up to ring distance 3 overlap (strong
// verifications, hundreds of inliers), farther candidates verify by
// accident (20 inliers) or not at all. Scores fall with ring distance,
// with a deterministic wobble that reorders pairs of one distance only.
struct RingScene {
  explicit RingScene(int num_images, int num_neighbours = 6) {
    for (int i = 0; i < num_images; ++i) image_ids.push_back(i + 1);
    for (int i = 0; i < num_images; ++i) {
      for (int d = 1; d <= num_neighbours; ++d) {
        const int j = (i + d) % num_images;
        const float wobble = 0.02f * static_cast<float>((i * 7 + d * 3) % 5);
        candidates.push_back({image_ids[i],
                              image_ids[j],
                              1.0f / static_cast<float>(d) - wobble});
      }
    }
  }

  int Distance(image_t a, image_t b) const {
    const int n = static_cast<int>(image_ids.size());
    const int d = std::abs(static_cast<int>(a) - static_cast<int>(b));
    return std::min(d, n - d);
  }
  bool IsStrongPair(image_t a, image_t b) const { return Distance(a, b) <= 3; }

  PairVerification Verify(const ImagePair& pair) const {
    PairVerification verification;
    verification.image_id1 = pair.first;
    verification.image_id2 = pair.second;
    const int d = Distance(pair.first, pair.second);
    if (d <= 3) {
      verification.config = 2;
      verification.num_inliers = 900 / d;
    } else if ((pair.first + pair.second) % 2 == 0) {
      verification.config = 2;
      verification.num_inliers = 18 + d;
    }
    return verification;
  }

  std::vector<image_t> image_ids;
  std::vector<PairCandidate> candidates;
};

// A dense capture: images on a line, every pair verifies with more than
// the strong floor, inliers falling with distance (1000 / d^2, at least 31).
struct LineScene {
  explicit LineScene(int num_images) {
    for (int i = 0; i < num_images; ++i) image_ids.push_back(i + 1);
    for (int i = 0; i < num_images; ++i) {
      for (int j = i + 1; j < num_images; ++j) {
        const float d = static_cast<float>(j - i);
        candidates.push_back({image_ids[i], image_ids[j], 1.0f / d});
      }
    }
  }
  static int Distance(const ImagePair& pair) {
    return std::abs(static_cast<int>(pair.first) -
                    static_cast<int>(pair.second));
  }
  static PairVerification Verify(const ImagePair& pair) {
    const int d = Distance(pair);
    PairVerification verification;
    verification.image_id1 = pair.first;
    verification.image_id2 = pair.second;
    verification.config = 2;
    verification.num_inliers = std::max(31, 1000 / (d * d));
    return verification;
  }
  std::vector<image_t> image_ids;
  std::vector<PairCandidate> candidates;
};

// The verification of `pair`: geometrically verified (config 2) with
// num_inliers inliers, or not verified with 0.
inline PairVerification Verified(const ImagePair& pair, size_t num_inliers) {
  PairVerification verification;
  verification.image_id1 = pair.first;
  verification.image_id2 = pair.second;
  if (num_inliers > 0) {
    verification.config = 2;
    verification.num_inliers = num_inliers;
  }
  return verification;
}

// Runs the generator to the end, verifying each block with `verify`;
// returns its blocks.
std::vector<std::vector<ImagePair>> RunToTheEnd(
    AdaptivePairGenerator* generator,
    const std::function<PairVerification(const ImagePair&)>& verify);

std::vector<ImagePair> Flatten(
    const std::vector<std::vector<ImagePair>>& blocks);

}  // namespace test
}  // namespace colmap_gcn

#include "verification/exact_matching.h"

#include <cmath>
#include <map>
#include <vector>

#include "math/dense_product.h"
#include "util/option_check.h"
#include "util/threading.h"

namespace colmap_gcn {
namespace {

// COLMAP normalises SIFT descriptors to unit length and scales them by 512
// before rounding to uint8.
constexpr float kDescriptorNormSquared = 512.0f * 512.0f;

typedef Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>
    FloatMatrix;

// Rows of descriptors1 per block of dot products: the block stays in cache
// while it is scanned.
constexpr Eigen::Index kBlockRows = 128;

// The best and second-best dot product of one feature, and the best's index
// (ties: the lower index, as the scan meets it first).
struct BestTwo {
  float best = -1;
  float second = -1;
  int index = -1;

  void Update(float dot, int j) {
    if (dot > best) {
      second = best;
      best = dot;
      index = j;
    } else if (dot > second) {
      second = dot;
    }
  }
};

// The match `candidates` proposes if it passes COLMAP's distance and ratio
// tests (angles between descriptors), else -1.
int Accepted(const BestTwo& candidates, const ExactMatchingOptions& options) {
  if (candidates.index < 0) return -1;
  const double best_distance = std::acos(
      std::min(1.0, candidates.best / double(kDescriptorNormSquared)));
  if (best_distance > options.max_distance) return -1;
  // A single candidate has no second best; COLMAP accepts it.
  if (candidates.second >= 0) {
    const double second_distance = std::acos(
        std::min(1.0, candidates.second / double(kDescriptorNormSquared)));
    if (best_distance >= options.max_ratio * second_distance) return -1;
  }
  return candidates.index;
}

}  // namespace

void ExactMatchingOptions::Check() const {
  CHECK_OPTION_INTERVAL(max_ratio, 0.0, false, 1.0, true);
  CHECK_OPTION_INTERVAL(max_distance, 0.0, false, M_PI, true);
}

FeatureMatches MatchDescriptorsExactly(const FeatureDescriptors& descriptors1,
                                       const FeatureDescriptors& descriptors2,
                                       const ExactMatchingOptions& options) {
  options.Check();
  if (descriptors1.rows() == 0 || descriptors2.rows() == 0) {
    return FeatureMatches();
  }
  THROW_CHECK(descriptors1.cols() == descriptors2.cols());
  const FloatMatrix d1 = descriptors1.cast<float>();
  const FloatMatrix d2 = descriptors2.cast<float>();
  const Eigen::Index n1 = d1.rows();
  const Eigen::Index n2 = d2.rows();
  const int dims = static_cast<int>(d1.cols());
  // One pass over the dot products finds both directions' candidates.
  std::vector<BestTwo> rows(n1);
  std::vector<BestTwo> cols(n2);
  FloatMatrix block;
  for (Eigen::Index start = 0; start < n1; start += kBlockRows) {
    const Eigen::Index count = std::min(kBlockRows, n1 - start);
    block.resize(count, n2);
    MultiplyABt(d1.row(start).data(),
                static_cast<int>(count),
                d2.data(),
                static_cast<int>(n2),
                dims,
                block.data());
    for (Eigen::Index r = 0; r < count; ++r) {
      const int i = static_cast<int>(start + r);
      const float* dots = block.row(r).data();
      BestTwo& row = rows[i];
      for (Eigen::Index j = 0; j < n2; ++j) {
        row.Update(dots[j], static_cast<int>(j));
        cols[j].Update(dots[j], i);
      }
    }
  }
  std::vector<int> forward(n1);
  for (Eigen::Index i = 0; i < n1; ++i) forward[i] = Accepted(rows[i], options);
  std::vector<int> backward;
  if (options.cross_check) {
    backward.resize(n2);
    for (Eigen::Index j = 0; j < n2; ++j) {
      backward[j] = Accepted(cols[j], options);
    }
  }
  std::vector<std::pair<uint32_t, uint32_t>> matches;
  for (size_t i = 0; i < forward.size(); ++i) {
    if (forward[i] < 0) continue;
    if (options.cross_check && backward[forward[i]] != static_cast<int>(i)) {
      continue;
    }
    matches.emplace_back(static_cast<uint32_t>(i),
                         static_cast<uint32_t>(forward[i]));
  }
  FeatureMatches result(matches.size(), 2);
  for (size_t m = 0; m < matches.size(); ++m) {
    result(m, 0) = matches[m].first;
    result(m, 1) = matches[m].second;
  }
  return result;
}

std::vector<FeatureMatches> MatchPairsExactly(
    const TwoViewGeometryStore& database,
    const std::vector<ImagePair>& pairs,
    const ExactMatchingOptions& options,
    const int num_threads) {
  options.Check();
  // The database is not thread-safe: the workers only read these.
  std::map<image_t, FeatureDescriptors> descriptors;
  for (const ImagePair& pair : pairs) {
    THROW_CHECK(pair.first < pair.second);
    for (const image_t id : {pair.first, pair.second}) {
      if (descriptors.count(id) == 0) {
        descriptors.emplace(id, database.ReadDescriptors(id));
      }
    }
  }
  std::vector<FeatureMatches> matches(pairs.size());
  ParallelFor(0, static_cast<int>(pairs.size()), num_threads, [&](int p) {
    matches[p] = MatchDescriptorsExactly(descriptors.at(pairs[p].first),
                                         descriptors.at(pairs[p].second),
                                         options);
  });
  return matches;
}

}  // namespace colmap_gcn

#include "verification/pair_verification.h"

#include <algorithm>
#include <map>

#include "util/option_check.h"
#include "util/random.h"
#include "util/threading.h"

namespace colmap_gcn {

void ExactVerificationOptions::Check() const {
  ransac.Check();
  CHECK_OPTION_GE(min_num_inliers, 0);
  CHECK_OPTION_NUM_THREADS(num_threads);
}

VerifiedTwoViewGeometry VerifyPairExactly(
    const FeatureMatches& matches,
    const Eigen::Matrix<float, Eigen::Dynamic, 2>& keypoints1,
    const Eigen::Matrix<float, Eigen::Dynamic, 2>& keypoints2,
    const image_t image_id1,
    const image_t image_id2,
    const ExactVerificationOptions& options) {
  THROW_CHECK(image_id1 < image_id2);
  VerifiedTwoViewGeometry geometry;
  geometry.pair_id = ImagePairToPairId(image_id1, image_id2);
  geometry.image_id1 = image_id1;
  geometry.image_id2 = image_id2;
  geometry.config = static_cast<int>(TwoViewGeometryConfig::kUndefined);
  // Eight matches at least: the RANSAC's sample.
  if (matches.rows() < std::max(8, options.min_num_inliers)) return geometry;
  Eigen::Matrix2Xd points1(2, matches.rows());
  Eigen::Matrix2Xd points2(2, matches.rows());
  for (Eigen::Index m = 0; m < matches.rows(); ++m) {
    if (matches(m, 0) >= keypoints1.rows() ||
        matches(m, 1) >= keypoints2.rows()) {
      ThrowError("pair ",
                 image_id1,
                 " ",
                 image_id2,
                 ": match ",
                 m,
                 " names keypoints ",
                 matches(m, 0),
                 " and ",
                 matches(m, 1),
                 " of ",
                 keypoints1.rows(),
                 " and ",
                 keypoints2.rows());
    }
    points1.col(m) = keypoints1.row(matches(m, 0)).transpose().cast<double>();
    points2.col(m) = keypoints2.row(matches(m, 1)).transpose().cast<double>();
  }
  const FundamentalRansacResult ransac = EstimateFundamentalRansac(
      points1, points2, options.ransac, SplitMix64Mix(geometry.pair_id));
  if (!ransac.success ||
      static_cast<int>(ransac.inliers.size()) < options.min_num_inliers) {
    return geometry;
  }
  geometry.config = static_cast<int>(TwoViewGeometryConfig::kUncalibrated);
  geometry.F = ransac.F;
  geometry.inliers.resize(ransac.inliers.size(), 2);
  for (size_t i = 0; i < ransac.inliers.size(); ++i) {
    geometry.inliers.row(i) = matches.row(ransac.inliers[i]);
  }
  return geometry;
}

std::vector<VerifiedTwoViewGeometry> VerifyPairsExactly(
    const TwoViewGeometryStore& database,
    const std::vector<ImagePair>& pairs,
    const ExactVerificationOptions& options) {
  options.Check();
  // Everything the workers read, read first: the database is not
  // thread-safe.
  std::map<image_t, Eigen::Matrix<float, Eigen::Dynamic, 2>> keypoints;
  std::vector<FeatureMatches> matches(pairs.size());
  for (size_t p = 0; p < pairs.size(); ++p) {
    if (pairs[p].first == pairs[p].second) continue;
    for (const image_t id : {pairs[p].first, pairs[p].second}) {
      if (keypoints.count(id) == 0) {
        keypoints.emplace(id, database.ReadKeypointPositions(id));
      }
    }
    matches[p] = database.ReadMatches(
        ImagePairToPairId(pairs[p].first, pairs[p].second));
  }
  std::vector<VerifiedTwoViewGeometry> results(pairs.size());
  ParallelFor(
      0, static_cast<int>(pairs.size()), options.num_threads, [&](int p) {
        const image_t id1 = std::min(pairs[p].first, pairs[p].second);
        const image_t id2 = std::max(pairs[p].first, pairs[p].second);
        if (id1 == id2) {
          results[p].pair_id = ImagePairToPairId(id1, id2);
          results[p].image_id1 = results[p].image_id2 = id1;
          return;
        }
        results[p] = VerifyPairExactly(matches[p],
                                       keypoints.at(id1),
                                       keypoints.at(id2),
                                       id1,
                                       id2,
                                       options);
      });
  return results;
}

}  // namespace colmap_gcn

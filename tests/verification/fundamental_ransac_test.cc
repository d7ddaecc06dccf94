#include "verification/fundamental_ransac.h"

#include <algorithm>
#include <set>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "util/error.h"
#include "util/random.h"

namespace colmap_gcn {
namespace {

double Uniform(uint64_t* state, double low, double high) {
  return low + (high - low) * (SplitMix64(state) % 1000001) / 1000000.0;
}

// num_inliers projections of points in front of two cameras 1 unit apart
// (focal 500, 640 x 480), then num_outliers random pixel pairs.
void TwoViewPoints(int num_inliers,
                   int num_outliers,
                   uint64_t seed,
                   Eigen::Matrix2Xd* points1,
                   Eigen::Matrix2Xd* points2) {
  uint64_t state = seed;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.2, Eigen::Vector3d(0.1, 1, 0).normalized())
          .toRotationMatrix();
  const Eigen::Vector3d t(-1, 0.1, 0.05);
  points1->resize(2, num_inliers + num_outliers);
  points2->resize(2, num_inliers + num_outliers);
  for (int i = 0; i < num_inliers; ++i) {
    const Eigen::Vector3d X(Uniform(&state, -2, 2),
                            Uniform(&state, -1.5, 1.5),
                            Uniform(&state, 4, 8));
    const Eigen::Vector3d x2 = R * X + t;
    points1->col(i) = 500 * X.hnormalized() + Eigen::Vector2d(320, 240);
    points2->col(i) = 500 * x2.hnormalized() + Eigen::Vector2d(320, 240);
  }
  for (int i = num_inliers; i < num_inliers + num_outliers; ++i) {
    points1->col(i) =
        Eigen::Vector2d(Uniform(&state, 0, 640), Uniform(&state, 0, 480));
    points2->col(i) =
        Eigen::Vector2d(Uniform(&state, 0, 640), Uniform(&state, 0, 480));
  }
}

TEST(FundamentalRansac, SeparatesInliersFromOutliers) {
  Eigen::Matrix2Xd p1, p2;
  TwoViewPoints(150, 150, 11, &p1, &p2);
  const FundamentalRansacResult result =
      EstimateFundamentalRansac(p1, p2, FundamentalRansacOptions(), 5);
  ASSERT_TRUE(result.success);
  const std::set<int> inliers(result.inliers.begin(), result.inliers.end());
  int true_found = 0;
  for (int i = 0; i < 150; ++i) true_found += inliers.count(i);
  EXPECT_EQ(true_found, 150);
  // A random pixel pair lies within 4 px of a random epipolar line now and
  // then; never many of them.
  EXPECT_LE(static_cast<int>(inliers.size()) - true_found, 10);
  // The refit includes the few stray pairs: true matches fit closely on
  // average, far inside the 4 px that admits them.
  double squared_error = 0;
  for (int i = 0; i < 150; ++i) {
    squared_error += SquaredSampsonError(result.F, p1.col(i), p2.col(i));
  }
  EXPECT_LT(squared_error / 150, 0.5);
  EXPECT_NEAR(result.F.determinant(), 0, 1e-9 * result.F.norm());
}

TEST(FundamentalRansac, SameSeedSameResultAndSeedsAgreeOnCleanData) {
  Eigen::Matrix2Xd p1, p2;
  TwoViewPoints(80, 120, 12, &p1, &p2);
  const FundamentalRansacOptions options;
  const FundamentalRansacResult a =
      EstimateFundamentalRansac(p1, p2, options, 7);
  const FundamentalRansacResult b =
      EstimateFundamentalRansac(p1, p2, options, 7);
  ASSERT_TRUE(a.success);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.num_trials, b.num_trials);
  EXPECT_TRUE(a.F == b.F);
}

TEST(FundamentalRansac, TooFewPointsOrPureNoiseFindLittle) {
  Eigen::Matrix2Xd p1, p2;
  TwoViewPoints(7, 0, 13, &p1, &p2);
  EXPECT_FALSE(
      EstimateFundamentalRansac(p1, p2, FundamentalRansacOptions(), 1).success);
  TwoViewPoints(0, 200, 14, &p1, &p2);
  const FundamentalRansacResult noise =
      EstimateFundamentalRansac(p1, p2, FundamentalRansacOptions(), 1);
  // Any eight points fit some F; random pairs add only a few more.
  EXPECT_LT(noise.inliers.size(), 30u);
  EXPECT_EQ(noise.num_trials, FundamentalRansacOptions().max_num_trials);
}

TEST(FundamentalRansac, CheckNamesTheBadOption) {
  FundamentalRansacOptions options;
  options.max_error = 0;
  try {
    options.Check();
    ADD_FAILURE() << "Check() accepted max_error 0";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("max_error"), std::string::npos);
  }
}

}  // namespace
}  // namespace colmap_gcn

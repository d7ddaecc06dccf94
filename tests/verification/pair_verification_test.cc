#include "verification/pair_verification.h"

#include <sqlite3.h>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "scene/colmap_scene_fixture.h"
#include "test_features.h"
#include "test_utils.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::ExecuteSql;
using test::kColmap38Schema;

void InsertBlobs(sqlite3* db,
                 const std::string& sql,
                 const void* data,
                 int bytes) {
  sqlite3_stmt* stmt = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr), SQLITE_OK)
      << sqlite3_errmsg(db);
  if (data != nullptr) {
    sqlite3_bind_blob(stmt, 1, data, bytes, SQLITE_TRANSIENT);
  }
  ASSERT_EQ(sqlite3_step(stmt), SQLITE_DONE) << sqlite3_errmsg(db);
  sqlite3_finalize(stmt);
}

// Three images: 1 and 2 see the same 120 points (their features listed in
// different orders, with 80 unrelated features each); image 3 sees
// something else. Returns the database path.
std::string WriteThreeImageDatabase(const std::string& dir) {
  const std::string path = JoinPaths(dir, "database.db");
  ExecuteSql(path, kColmap38Schema);
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  uint64_t state = 42;
  constexpr int kShared = 120;
  constexpr int kOwn = 80;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Matrix<float, 1, 128>> directions;
  for (int p = 0; p < kShared; ++p) {
    points.emplace_back(-2 + 4 * (SplitMix64(&state) % 1000) / 1000.0,
                        -1.5 + 3 * (SplitMix64(&state) % 1000) / 1000.0,
                        4 + 4 * (SplitMix64(&state) % 1000) / 1000.0);
    directions.push_back(test::RandomDescriptorDirection(&state));
  }
  const Eigen::Matrix3d R2 =
      Eigen::AngleAxisd(0.15, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d t2(-0.8, 0, 0.1);
  const double params[4] = {500, 500, 320, 240};
  for (int image = 1; image <= 3; ++image) {
    const int n = kShared + kOwn;
    Eigen::Matrix<float, Eigen::Dynamic, 2, Eigen::RowMajor> keypoints(n, 2);
    FeatureDescriptors descriptors(n, 128);
    for (int f = 0; f < n; ++f) {
      // Image 2 lists the shared points backwards.
      const int p = image == 2 && f < kShared ? kShared - 1 - f : f;
      Eigen::Vector2d pixel;
      Eigen::Matrix<float, 1, 128> direction;
      if (f < kShared && image != 3) {
        const Eigen::Vector3d X = image == 1 ? points[p] : R2 * points[p] + t2;
        pixel = 500 * X.hnormalized() + Eigen::Vector2d(320, 240);
        direction = test::Perturbed(directions[p], 0.1, &state);
      } else {
        pixel =
            Eigen::Vector2d(SplitMix64(&state) % 640, SplitMix64(&state) % 480);
        direction = test::RandomDescriptorDirection(&state);
      }
      keypoints.row(f) = pixel.cast<float>().transpose();
      test::SetDescriptor(direction, &descriptors, f);
    }
    const std::string id = std::to_string(image);
    InsertBlobs(db,
                "INSERT INTO cameras VALUES (" + id + ", 1, 640, 480, ?, 1)",
                params,
                sizeof(params));
    InsertBlobs(db,
                "INSERT INTO images (image_id, name, camera_id) VALUES (" + id +
                    ", 'img" + id + ".jpg', " + id + ")",
                nullptr,
                0);
    InsertBlobs(db,
                "INSERT INTO keypoints VALUES (" + id + ", " +
                    std::to_string(n) + ", 2, ?)",
                keypoints.data(),
                static_cast<int>(keypoints.size() * sizeof(float)));
    InsertBlobs(db,
                "INSERT INTO descriptors VALUES (" + id + ", " +
                    std::to_string(n) + ", 128, ?)",
                descriptors.data(),
                static_cast<int>(descriptors.size()));
  }
  sqlite3_close(db);
  // The matches table, as gcn_matcher has COLMAP import it.
  const std::vector<ImagePair> pairs = {{1, 2}, {1, 3}, {2, 3}};
  std::vector<FeatureMatches> matches;
  {
    const TwoViewGeometryStore store(path);
    matches = MatchPairsExactly(store, pairs, ExactMatchingOptions(), 1);
  }
  EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  for (size_t p = 0; p < pairs.size(); ++p) {
    InsertBlobs(
        db,
        "INSERT INTO matches VALUES (" +
            std::to_string(ImagePairToPairId(pairs[p].first, pairs[p].second)) +
            ", " + std::to_string(matches[p].rows()) + ", 2, ?)",
        matches[p].data(),
        static_cast<int>(matches[p].size() * sizeof(uint32_t)));
  }
  sqlite3_close(db);
  return path;
}

TEST(PairVerification, VerifiesTheOverlappingPairAndNotTheOthers) {
  TemporaryDirectory dir("colmap_gcn_pair_verification");
  const TwoViewGeometryStore database(WriteThreeImageDatabase(dir.Path()));
  const std::vector<VerifiedTwoViewGeometry> results = VerifyPairsExactly(
      database, {{1, 2}, {1, 3}, {3, 2}}, ExactVerificationOptions());
  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[0].config,
            static_cast<int>(TwoViewGeometryConfig::kUncalibrated));
  // Every shared point, each matched to itself (image 2 lists them
  // backwards).
  ASSERT_GE(results[0].inliers.rows(), 115);
  int correct = 0;
  for (Eigen::Index m = 0; m < results[0].inliers.rows(); ++m) {
    correct += results[0].inliers(m, 0) < 120 &&
               results[0].inliers(m, 1) == 119 - results[0].inliers(m, 0);
  }
  EXPECT_GE(correct, 115);
  EXPECT_EQ(results[1].config, 0);
  EXPECT_EQ(results[1].inliers.rows(), 0);
  EXPECT_EQ(results[2].config, 0);
  // Either order names the pair by its smaller id first.
  EXPECT_EQ(results[2].image_id1, 2u);
  EXPECT_EQ(results[2].image_id2, 3u);
}

TEST(PairVerification, SameResultsForAnyThreadCountAndPairOrder) {
  TemporaryDirectory dir("colmap_gcn_pair_verification");
  const TwoViewGeometryStore database(WriteThreeImageDatabase(dir.Path()));
  ExactVerificationOptions one;
  one.num_threads = 1;
  ExactVerificationOptions two;
  two.num_threads = 2;
  const auto a = VerifyPairsExactly(database, {{1, 2}, {1, 3}, {2, 3}}, one);
  const auto b = VerifyPairsExactly(database, {{3, 2}, {2, 1}, {3, 1}}, two);
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  const std::vector<std::pair<int, int>> same = {{0, 1}, {1, 2}, {2, 0}};
  for (const auto& [i, j] : same) {
    EXPECT_EQ(a[i].pair_id, b[j].pair_id);
    EXPECT_EQ(a[i].config, b[j].config);
    EXPECT_TRUE(a[i].inliers == b[j].inliers);
    EXPECT_TRUE(a[i].F == b[j].F);
  }
}

TEST(PairVerification, MatchesRepeatForAnyThreadCount) {
  TemporaryDirectory dir("colmap_gcn_pair_verification");
  const TwoViewGeometryStore database(WriteThreeImageDatabase(dir.Path()));
  const std::vector<ImagePair> pairs = {{1, 2}, {1, 3}, {2, 3}};
  const auto one =
      MatchPairsExactly(database, pairs, ExactMatchingOptions(), 1);
  const auto two =
      MatchPairsExactly(database, pairs, ExactMatchingOptions(), 2);
  ASSERT_EQ(one.size(), 3u);
  for (size_t p = 0; p < pairs.size(); ++p) EXPECT_TRUE(one[p] == two[p]);
  EXPECT_GE(one[0].rows(), 115);
}

TEST(PairVerification, APairWithoutMatchesIsUnverified) {
  TemporaryDirectory dir("colmap_gcn_pair_verification");
  const std::string path = WriteThreeImageDatabase(dir.Path());
  ExecuteSql(path, "DELETE FROM matches");
  const auto results = VerifyPairsExactly(
      TwoViewGeometryStore(path), {{1, 2}}, ExactVerificationOptions());
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].config, 0);
}

TEST(PairVerification, MinNumInliersAboveTheOverlapLeavesThePairUnverified) {
  TemporaryDirectory dir("colmap_gcn_pair_verification");
  const TwoViewGeometryStore database(WriteThreeImageDatabase(dir.Path()));
  ExactVerificationOptions options;
  options.min_num_inliers = 150;
  const auto results = VerifyPairsExactly(database, {{1, 2}}, options);
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].config, 0);
}

}  // namespace
}  // namespace colmap_gcn

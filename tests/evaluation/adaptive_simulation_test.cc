#include "evaluation/adaptive_simulation.h"

#include <gtest/gtest.h>

#include "scene/colmap_scene_fixture.h"
#include "test_utils.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::ExecuteSql;
using test::kColmap38Schema;

// Four images; pairs (1,2) 200 inliers, (1,3) 20, (2,4) 10 inliers (below
// COLMAP's 15: not verified), (3,4) degenerate config 0; no row for others.
std::string MakeDatabase(const TemporaryDirectory& dir,
                         const std::vector<std::string>& names) {
  const std::string path = JoinPaths(dir.Path(), "database.db");
  ExecuteSql(path, kColmap38Schema);
  std::string sql =
      "INSERT INTO cameras VALUES (1, 0, 100, 80, NULL, 0);"
      "INSERT INTO images (image_id, name, camera_id) VALUES ";
  for (size_t i = 0; i < names.size(); ++i) {
    sql += (i > 0 ? ", (" : "(") + std::to_string(i + 1) + ", '" + names[i] +
           "', 1)";
  }
  sql += ";";
  const auto geometry = [](image_t a, image_t b, int config, int rows) {
    return "INSERT INTO two_view_geometries (pair_id, rows, cols, config) "
           "VALUES (" +
           std::to_string(ImagePairToPairId(a, b)) + ", " +
           std::to_string(rows) + ", 2, " + std::to_string(config) + ");";
  };
  sql += geometry(1, 2, 2, 200) + geometry(1, 3, 2, 20) +
         geometry(2, 4, 2, 10) + geometry(3, 4, 0, 0);
  ExecuteSql(path, sql);
  return path;
}

TEST(VerificationTable, LooksUpEveryPairInBothOrders) {
  const TemporaryDirectory dir("colmap_gcn_simulation");
  const Database database(
      MakeDatabase(dir, {"a.jpg", "b.jpg", "c.jpg", "d.jpg"}));
  const VerificationTable table(database);
  EXPECT_EQ(table.Lookup(2, 1).num_inliers, 200u);
  EXPECT_EQ(table.Lookup(1, 3).num_inliers, 20u);
  EXPECT_EQ(table.Lookup(1, 4).num_inliers, 0u);  // no row
  EXPECT_EQ(table.Name(3), "c.jpg");
  EXPECT_FALSE(table.IsCollection());
}

TEST(VerificationTable, EvaluatesAPairSetAtTheStrongCut) {
  const TemporaryDirectory dir("colmap_gcn_simulation");
  const Database database(
      MakeDatabase(dir, {"p__a.jpg", "p__b.jpg", "q__c.jpg", "q__d.jpg"}));
  const VerificationTable table(database);
  ASSERT_TRUE(table.IsCollection());
  // Duplicates and self pairs count once / not at all.
  const PairSetQuality quality = EvaluatePairSet(
      {{1, 2}, {2, 1}, {1, 3}, {2, 4}, {3, 4}, {1, 1}}, table, nullptr, 30);
  EXPECT_EQ(quality.num_pairs, 4u);
  EXPECT_EQ(quality.num_verified, 2u);  // (1,2) and (1,3)
  EXPECT_EQ(quality.num_strong, 1u);    // (1,2) only
  EXPECT_EQ(quality.num_images_with_strong, 2u);
  EXPECT_EQ(quality.num_cross_scene, 2u);   // (1,3) and (2,4)
  EXPECT_EQ(quality.num_images_grown, 2u);  // the seed pair
  // At 15 inliers (1,3) is strong too, but image 3 has one partner in the
  // model grown from (1,2): three images with a strong pair, two grown.
  const PairSetQuality low =
      EvaluatePairSet({{1, 2}, {1, 3}}, table, nullptr, 15);
  EXPECT_EQ(low.num_images_with_strong, 3u);
  EXPECT_EQ(low.num_images_grown, 2u);
}

TEST(VerificationTable, StrongPairsAreTheVerifiedOnesAtTheCut) {
  const TemporaryDirectory dir("colmap_gcn_simulation");
  const Database database(
      MakeDatabase(dir, {"a.jpg", "b.jpg", "c.jpg", "d.jpg"}));
  const VerificationTable table(database);
  EXPECT_EQ(table.StrongPairs(30), (std::vector<ImagePair>{{1, 2}}));
  // (2,4) has 10 inliers (not verified), (3,4) a degenerate config.
  EXPECT_EQ(table.StrongPairs(15), (std::vector<ImagePair>{{1, 2}, {1, 3}}));
  EXPECT_TRUE(table.StrongPairs(201).empty());
}

TEST(VerificationTable, NamesWithUnderscoresAloneAreNoCollection) {
  // Web photos of one place may have "__" in their names.
  const TemporaryDirectory dir("colmap_gcn_simulation");
  const Database database(MakeDatabase(
      dir, {"023_resize___1_.jpg", "001.jpg", "002.jpg", "003.jpg"}));
  const VerificationTable table(database);
  EXPECT_FALSE(table.IsCollection());
  EXPECT_EQ(
      EvaluatePairSet({{1, 2}, {1, 3}}, table, nullptr, 30).num_cross_scene,
      0u);
}

}  // namespace
}  // namespace colmap_gcn
